// SPDX-License-Identifier: LGPL-3.0-or-later
// The 3D view of the planning app (three.js): the neutral cap with the
// incision (tissue to be removed tinted, planes P1, P1' and P2, points A, B,
// C, D), and the skin surfaces of a finished job, pre and post side by side
// or overlaid. Model coordinates (x lateral, y out of the chest, z up; m)
// are drawn in mm with three.js's y up: (x, y, z) -> (x, z, y).
import * as THREE from "three";
import { OrbitControls } from "/three/OrbitControls.js";

const SKIN = new THREE.Color(0xe8b9a0), CUT = new THREE.Color(0xc0392b), POST = new THREE.Color(0x7fb3d5);
export const POINT_COLOURS = { A: 0x1e8449, B: 0x2471a3, C: 0x7d3c98, D: 0xd68910 };

const toScene = (p) => new THREE.Vector3(1e3 * p[0], 1e3 * p[2], 1e3 * p[1]);

export class View3D {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(1);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xffffff);
    this.camera = new THREE.PerspectiveCamera(35, 1, 1, 5000);
    this.camera.position.set(260, 90, 330);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener("change", () => this.render());
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x887766, 0.9));
    const sun = new THREE.DirectionalLight(0xffffff, 0.55); // from over the viewer's shoulder
    sun.position.set(0.3, 0.6, 1);
    this.camera.add(sun);
    this.scene.add(this.camera);
    this.content = new THREE.Group();
    this.scene.add(this.content);
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  resize() {
    const w = Math.max(this.container.clientWidth, 100), h = Math.max(this.container.clientHeight, 100);
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.render();
  }

  // With `split` (two groups of the content), each group in its own half of
  // the canvas, seen by the one camera: linked views.
  render() {
    const size = this.renderer.getSize(new THREE.Vector2());
    if (!this.split) {
      this.camera.aspect = size.x / size.y;
      this.camera.updateProjectionMatrix();
      this.renderer.render(this.scene, this.camera);
      return;
    }
    const half = Math.floor(size.x / 2);
    this.camera.aspect = half / size.y;
    this.camera.updateProjectionMatrix();
    this.renderer.setScissorTest(true);
    this.split.forEach((group, k) => {
      this.split.forEach((g) => { g.visible = g === group; });
      this.renderer.setViewport(k * half, 0, half - 1, size.y);
      this.renderer.setScissor(k * half, 0, half - 1, size.y);
      this.renderer.render(this.scene, this.camera);
    });
    for (const g of this.split) g.visible = true;
    this.renderer.setScissorTest(false);
    this.renderer.setViewport(0, 0, size.x, size.y);
  }

  clear() {
    this.plan = null;
    this.split = null;
    for (const o of [...this.content.children]) {
      this.content.remove(o);
      o.traverse((c) => { if (c.geometry) c.geometry.dispose(); if (c.material) { if (c.material.map) c.material.map.dispose(); c.material.dispose(); } });
    }
  }

  // The neutral cap (R, H) of the full breast; with `incision` (the answer of
  // /api/incision/check) the removed tissue is tinted and the planes and
  // points drawn. A plan on the same cap is updated in place: the cap's
  // colours, the planes' corners and the points' positions, no new geometry.
  showPlan(cap, incision) {
    if (!this.plan || this.plan.R !== cap.R || this.plan.H !== cap.H) {
      this.clear();
      this.plan = new PlanObjects(cap);
      this.content.add(this.plan.group);
    }
    this.plan.update(incision);
    if (!this.framed) this.frame(new THREE.Vector3(1, 0.35, 1.25));
    this.framed = "plan";
    this.render();
  }

  // The scene drawn at w x h pixels, seen from `direction` (scene axes: x
  // lateral, y up, z out of the chest) if given, framed with `margin`
  // (frame()): a PNG, base64 without the data: prefix. The view is left as it was.
  snapshot(w, h, direction, margin = 0.4) {
    const camera = this.camera.clone(), target = this.controls.target.clone();
    this.renderer.setSize(w, h, false);
    if (direction) this.frame(new THREE.Vector3(...direction), margin);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.render();
    const png = this.renderer.domElement.toDataURL("image/png").split(",")[1];
    this.camera.position.copy(camera.position);
    this.camera.quaternion.copy(camera.quaternion);
    this.controls.target.copy(target);
    this.resize();
    return png;
  }

  // Aim the camera at the content from `direction` (an array, scene axes).
  look(direction) {
    this.frame(new THREE.Vector3(...direction), 0.4);
  }

  // Aim the camera at the content from `direction` at a distance that shows
  // all of it: `margin` x the content's diagonal fills half the field of
  // view (0.4 for pictures, 0.6 with room to turn it on the page); in a view
  // narrower than high, at least far enough for its width to fit across.
  frame(direction, margin = 0.6) {
    const box = new THREE.Box3().setFromObject(this.content);
    const centre = box.getCenter(new THREE.Vector3()), size = box.getSize(new THREE.Vector3()).length();
    const tanHalf = Math.tan((this.camera.fov * Math.PI) / 360);
    let distance = (margin * size) / tanHalf;
    const canvas = this.renderer.getSize(new THREE.Vector2());
    const aspect = (this.split ? canvas.x / 2 : canvas.x) / canvas.y;
    if (aspect < 1) { // a view narrower than high: the content's width across the view must fit too
      const right = new THREE.Vector3().crossVectors(new THREE.Vector3(0, 1, 0), direction.clone().normalize());
      if (right.lengthSq() < 1e-6) right.set(1, 0, 0);
      right.normalize();
      let half = 0;
      for (const x of [box.min.x, box.max.x]) for (const y of [box.min.y, box.max.y]) for (const z of [box.min.z, box.max.z])
        half = Math.max(half, Math.abs(new THREE.Vector3(x, y, z).sub(centre).dot(right)));
      distance = Math.max(distance, (1.15 * half) / (tanHalf * aspect));
    }
    this.controls.target.copy(centre);
    this.camera.position.copy(centre).addScaledVector(direction.clone().normalize(), distance);
    this.camera.lookAt(centre);
    this.controls.update();
  }

  // Skin surfaces (surface_<posture>.json documents; a half model mirrored to
  // the full breast), seen in profile: `mode` "side" (pre, then post further out of the
// chest) or "overlay".
  showSurfaces(pre, post, mode) {
    this.clear();
    const shift = mode === "side" && post ? 120 : 0;
    if (pre) this.content.add(surfaceMesh(pre, SKIN, -shift / 2, post && mode === "overlay" ? 0.45 : 1));
    if (post) this.content.add(surfaceMesh(post, POST, shift / 2, 1));
    if (this.framed !== mode) this.frame(new THREE.Vector3(-1, 0.1, 0)); // in profile, pre left: projection and ptosis
    this.framed = mode;
    this.render();
  }

  // Both breasts on the chest, in the patient's frame (mm; the sternal notch
  // at the origin, the patient's left to +x, up +y, forward +z): each of
  // `breasts` ({side, notch, pre, post, nipples, drawing}: the notch in that
  // breast's frame, its standing surfaces, the plan's drawing; a scanned
  // breast is drawn before surgery as its scan, drawing.scan) placed by its
  // notch, the right one mirrored. `mode`: "before", "after", "both" (before
  // and after in two linked views, one camera) or "overlay" (before
  // translucent). The chest is a translucent plane; the notch and the
  // nipples are marked; with `tapes`, SN-N and N-IMF are drawn and labelled
  // on each stage and the skin marking on the breast before surgery.
  showTorso(breasts, mode, tapes = true) {
    this.clear();
    const stages = mode === "both" || mode === "overlay" ? ["pre", "post"] : [mode === "after" ? "post" : "pre"];
    const groups = stages.map((stage) => {
      const group = new THREE.Group();
      for (const b of breasts) {
        const scan = stage === "pre" && b.drawing && b.drawing.scan; // a scanned breast: before is its scan
        const doc = scan ? scan.skin : b[stage];
        if (!doc) continue;
        const place = (p) => [(b.side === "left" ? 1 : -1) * (p[0] - b.notch[0]) * 1e3, (p[2] - b.notch[2]) * 1e3,
                              p[1] * 1e3];
        group.add(placedMesh(doc, stage === "pre" ? SKIN : POST, place, mode === "overlay" && stage === "pre" ? 0.45 : 1));
        const nipple = scan ? scan.before.n_imf[0] : b.nipples && b.nipples[stage];
        if (nipple) group.add(marker(place(nipple), 0x3b3040));
        if (tapes && mode !== "overlay" && b.drawing) group.add(drawingFor(b, stage, place));
      }
      if (stage === "pre" || mode !== "overlay") group.add(marker([0, 0, 0], 0x2471a3), chestPlane(0)); // notch, chest
      this.content.add(group);
      return group;
    });
    this.split = mode === "both" ? groups : null;
    if (this.framed !== "torso") this.frame(new THREE.Vector3(0, 0.1, 1), 0.7);
    this.framed = "torso";
    this.render();
  }

  // The camera's presets of the torso: front, side (from the patient's left),
  // oblique, below; "reset" frames it from the front again.
  preset(name) {
    const d = { front: [0, 0.1, 1], side: [1, 0.05, 0], oblique: [0.7, 0.15, 0.7], below: [0, -1, 0.35],
                reset: [0, 0.1, 1] }[name];
    if (d) this.frame(new THREE.Vector3(...d), 0.7);
    this.render();
  }

  // The number of vertices drawn (meshes of the content).
  drawnVertices() {
    let n = 0;
    this.content.traverse((o) => { if (o.isMesh) n += o.geometry.getAttribute("position").count; });
    return n;
  }

  // A scanned (full) breast's skin, a surface_<posture>.json document, seen
  // obliquely from the front and the side.
  showScan(doc) {
    this.clear();
    this.content.add(surfaceMesh(doc, SKIN, 0, 1));
    if (this.framed !== "scan") this.frame(new THREE.Vector3(1.1, 0.3, 0.8)); // from the front and the side: its projection
    this.framed = "scan";
    this.render();
  }
}

// The objects of a plan on one cap: the cap (its model points kept for
// recolouring), the base ring, the planes P1, P1', P2 and the points A-D
// (with their mirrors), all updated in place by update().
class PlanObjects {
  constructor(cap) {
    this.R = cap.R;
    this.H = cap.H;
    this.group = new THREE.Group();
    [this.cap, this.capPoints] = capMesh(cap);
    this.group.add(this.cap, baseRing(cap.R));
    this.planes = [0x1e8449, 0x1e8449, 0x7d3c98].map((c) => planeQuad(c));
    this.group.add(...this.planes);
    const ball = new THREE.SphereGeometry(2.5, 16, 12);
    this.balls = {};
    for (const name of ["A", "B", "C", "D"]) {
      const material = new THREE.MeshBasicMaterial({ color: POINT_COLOURS[name] });
      this.balls[name] = [new THREE.Mesh(ball, material), new THREE.Mesh(ball, material)];
      this.group.add(...this.balls[name]);
    }
  }

  update(incision) {
    const colour = this.cap.geometry.getAttribute("color");
    this.capPoints.forEach((p, k) => {
      const c = incision && removed(incision, p) ? CUT : SKIN;
      colour.setXYZ(k, c.r, c.g, c.b);
    });
    colour.needsUpdate = true;
    for (const o of [...this.planes, ...Object.values(this.balls).flat()]) o.visible = !!incision;
    if (!incision) return;
    for (const [name, [ball, mirror]] of Object.entries(this.balls)) {
      const p = incision[name];
      ball.position.copy(toScene(p));
      mirror.position.copy(toScene([-p[0], p[1], p[2]]));
      mirror.visible = p[0] !== 0;
    }
    const n1 = incision.P1.normal;
    setPlaneQuad(this.planes[0], n1, incision.P1.offset, this.R);
    setPlaneQuad(this.planes[1], [-n1[0], n1[1], n1[2]], incision.P1.offset, this.R);
    setPlaneQuad(this.planes[2], incision.P2.normal, incision.P2.offset, this.R);
  }
}

function capMesh(cap) {
  const R = cap.R, H = cap.H, Rs = (R * R + H * H) / (2 * H), yc = H - Rs;
  const amax = Math.acos((Rs - H) / Rs), nA = 40, nB = 96;
  const pos = [], points = [], idx = [];
  for (let i = 0; i <= nA; i++) {
    const a = (amax * i) / nA;
    for (let j = 0; j <= nB; j++) {
      const b = (2 * Math.PI * j) / nB;
      const p = [Rs * Math.sin(a) * Math.cos(b), yc + Rs * Math.cos(a), Rs * Math.sin(a) * Math.sin(b)];
      const v = toScene(p);
      pos.push(v.x, v.y, v.z);
      points.push(p);
    }
  }
  for (let i = 0; i < nA; i++)
    for (let j = 0; j < nB; j++) {
      const k = i * (nB + 1) + j;
      idx.push(k, k + nB + 1, k + 1, k + 1, k + nB + 1, k + nB + 2);
    }
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.Float32BufferAttribute(pos, 3));
  g.setAttribute("color", new THREE.Float32BufferAttribute(new Float32Array(pos.length), 3));
  g.setIndex(idx);
  g.computeVertexNormals();
  return [new THREE.Mesh(g, new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide })), points];
}

// In the removed tissue: beyond P1 (or its mirror) or beyond P2 (n . p < offset).
function removed(inc, p) {
  const q = [Math.abs(p[0]), p[1], p[2]];
  const dot = (n) => n[0] * q[0] + n[1] * q[1] + n[2] * q[2];
  return dot(inc.P1.normal) < inc.P1.offset || dot(inc.P2.normal) < inc.P2.offset;
}

function planeQuad(colour) {
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.Float32BufferAttribute(new Float32Array(12), 3));
  g.setIndex([0, 1, 2, 0, 2, 3]);
  return new THREE.Mesh(g, new THREE.MeshBasicMaterial({ color: colour, transparent: true, opacity: 0.18,
                                                          side: THREE.DoubleSide, depthWrite: false }));
}

// The square of side 2R on the plane n . x = offset, centred at offset n.
function setPlaneQuad(quad, n, offset, R) {
  const normal = new THREE.Vector3(n[0], n[1], n[2]).normalize();
  const centre = normal.clone().multiplyScalar(offset);
  const helper = Math.abs(normal.x) < 0.9 ? new THREE.Vector3(1, 0, 0) : new THREE.Vector3(0, 1, 0);
  const u = new THREE.Vector3().crossVectors(normal, helper).normalize(), v = new THREE.Vector3().crossVectors(normal, u);
  const position = quad.geometry.getAttribute("position");
  [[-1, -1], [1, -1], [1, 1], [-1, 1]].forEach(([a, b], k) => {
    const c = toScene(centre.clone().addScaledVector(u, a * R).addScaledVector(v, b * R).toArray());
    position.setXYZ(k, c.x, c.y, c.z);
  });
  position.needsUpdate = true;
  quad.geometry.computeBoundingSphere();
}

function baseRing(R) {
  const pts = [];
  for (let i = 0; i <= 96; i++) pts.push(toScene([R * Math.cos((2 * Math.PI * i) / 96), 0, R * Math.sin((2 * Math.PI * i) / 96)]));
  return new THREE.Line(new THREE.BufferGeometry().setFromPoints(pts), new THREE.LineBasicMaterial({ color: 0x555555 }));
}

// A surface document drawn with its vertices mapped by `place` (model point
// [m] -> scene [x, y, z] in mm): a half model (mirror_x, the default) with
// its mirror image, a full breast (mirror_x false: a scan) as it is.
function placedMesh(doc, colour, place, opacity = 1) {
  const v = doc.vertices, t = doc.triangles, pos = [];
  const sides = doc.mirror_x === false ? [1] : [1, -1];
  for (const side of sides)
    for (let i = 0; i < v.length; i += 3) pos.push(...place([side * v[i], v[i + 1], v[i + 2]]));
  const n = v.length / 3, idx = [...t];
  if (sides.length === 2) for (let k = 0; k < t.length; k += 3) idx.push(t[k] + n, t[k + 2] + n, t[k + 1] + n);
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.Float32BufferAttribute(pos, 3));
  g.setIndex(idx);
  g.computeVertexNormals();
  return new THREE.Mesh(g, new THREE.MeshLambertMaterial({ color: colour, side: THREE.DoubleSide,
                                                           transparent: opacity < 1, opacity }));
}

function marker(p, colour) {
  const m = new THREE.Mesh(new THREE.SphereGeometry(4, 12, 8), new THREE.MeshBasicMaterial({ color: colour }));
  m.position.set(...p);
  return m;
}

const TAPE = 0x1a5276, MARKER_PEN = 0x6c3483;

// The drawing of one breast at one stage: its tapes (SN-N from the notch, N-IMF
// down the meridian) labelled in cm, and before surgery the Wise marking.
function drawingFor(b, stage, place) {
  const scan = stage === "pre" && b.drawing.scan; // on a scanned breast: the tapes and the marking on its scan
  const group = new THREE.Group(), d = scan ? scan.before : b.drawing[stage === "pre" ? "before" : "after"];
  // SN-N's label on its tape, 40 % of the way from the notch; N-IMF's under the fold.
  const sn = d.sn_n.map(place), fold = d.n_imf.map(place);
  group.add(tube(sn, TAPE, 0.9), tube(fold, TAPE, 0.9));
  const at = sn[0].map((v, k) => v + 0.4 * (sn[sn.length - 1][k] - v));
  group.add(label3d(`SN-N ${(d.sn_n_mm / 10).toFixed(1)} cm`, [at[0], at[1], at[2] + 25]));
  const end = fold[fold.length - 1];
  group.add(label3d(`N-IMF ${(d.n_imf_mm / 10).toFixed(1)} cm`, [end[0], end[1] - 16, end[2] + 25]));
  if (stage === "pre")
    for (const line of (scan || b.drawing).marking) group.add(tube(line.map(place), MARKER_PEN, 0.7));
  return group;
}

// A line on the skin as a thin tube (visible from every side, no z-fighting).
function tube(points, colour, radius) {
  const curve = new THREE.CatmullRomCurve3(points.map((p) => new THREE.Vector3(...p)));
  return new THREE.Mesh(new THREE.TubeGeometry(curve, Math.max(8, 2 * points.length), radius, 6, false),
                        new THREE.MeshBasicMaterial({ color: colour }));
}

// A text label facing the camera, 80 x 15 mm, drawn over everything.
function label3d(text, position) {
  const canvas = document.createElement("canvas");
  canvas.width = 320;
  canvas.height = 60;
  const g = canvas.getContext("2d");
  g.fillStyle = "rgba(255, 255, 255, 0.8)";
  g.fillRect(0, 0, 320, 60);
  g.fillStyle = "#1a5276";
  g.font = "bold 38px system-ui, sans-serif";
  g.textAlign = "center";
  g.textBaseline = "middle";
  g.fillText(text, 160, 31);
  const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: new THREE.CanvasTexture(canvas), depthTest: false }));
  sprite.scale.set(80, 15, 1);
  sprite.position.set(...position);
  sprite.renderOrder = 10;
  return sprite;
}

// The chest wall: a translucent plane z = 0 from the notch down, centred at x = `shift`.
function chestPlane(shift) {
  const m = new THREE.Mesh(new THREE.PlaneGeometry(340, 400),
                           new THREE.MeshBasicMaterial({ color: 0xd9c8be, transparent: true, opacity: 0.35,
                                                         side: THREE.DoubleSide, depthWrite: false }));
  m.position.set(shift, -170, -1);
  return m;
}

// A surface document in model coordinates, moved `shift` mm out of the chest.
function surfaceMesh(doc, colour, shift, opacity) {
  return placedMesh(doc, colour, (p) => { const q = toScene(p); return [q.x, q.y, q.z + shift]; }, opacity);
}
