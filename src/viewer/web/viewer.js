// SPDX-License-Identifier: LGPL-3.0-or-later
// breastsim 3D page: the full breast of each posture (a half model, x >= 0,
// with its mirror image x -> -x; a full breast, e.g. a scan, as it is),
// coloured by the displacement from the neutral shape [mm].
// Data: window.BREASTSIM_DATA = {sets: [{label, surfaces: [{posture,
// theta_deg, mirror_x, vertices, vertices_ref, triangles, fields:
// {<name>_mm: [...]}}]}]} (lengths in m; mirror_x absent: a half model);
// every per-vertex field (displacement_mm, or e.g. a residual) can colour
// the surface. Exposes window.breastsimViewer for tests.
(function () {
  "use strict";
  const data = window.BREASTSIM_DATA;
  const state = { set: 0, posture: data.sets[0].surfaces[0].posture,
                  colour: "displacement_mm", neutral: false };
  const BACKGROUND = 0xf4f4f4;

  // Viridis, sampled at 9 points.
  const VIRIDIS = [[68, 1, 84], [71, 44, 122], [59, 81, 139], [44, 113, 142], [33, 144, 141],
                   [39, 173, 129], [92, 200, 99], [170, 220, 50], [253, 231, 37]];
  function colormap(t) {
    t = Math.min(1, Math.max(0, t)) * (VIRIDIS.length - 1);
    const i = Math.min(Math.floor(t), VIRIDIS.length - 2), f = t - i;
    return VIRIDIS[i].map((c, k) => (c + f * (VIRIDIS[i + 1][k] - c)) / 255);
  }

  // Colour range of each field over every surface, so toggles compare.
  const vmax = {};
  for (const s of data.sets)
    for (const surf of s.surfaces)
      for (const [name, values] of Object.entries(surf.fields))
        for (const v of values) vmax[name] = Math.max(vmax[name] || 1e-6, v);
  const fieldLabel = name => name.replace(/_mm$/, " [mm]").replace(/_/g, " ");

  // Full breast: a half surface and its mirror image (x -> -x, reversed
  // winding), or a full surface as it is.
  const mirrored = surf => surf.mirror_x !== false;
  function fullGeometry(surf, key, field) {
    const v = surf[key], tri = surf.triangles, values = field && surf.fields[field];
    const n = v.length / 3, copies = mirrored(surf) ? 2 : 1;
    const pos = new Float32Array(3 * copies * n), col = new Float32Array(3 * copies * n);
    for (let i = 0; i < n; ++i) {
      const rgb = values ? colormap(values[i] / vmax[field]) : [0.93, 0.76, 0.66];
      for (let k = 0; k < copies; ++k)
        for (let c = 0; c < 3; ++c) {
          pos[3 * (k * n + i) + c] = (k === 1 && c === 0 ? -1e3 : 1e3) * v[3 * i + c];
          col[3 * (k * n + i) + c] = rgb[c];
        }
    }
    const index = new Uint32Array(copies * tri.length);
    for (let t = 0; t < tri.length; t += 3) {
      index.set([tri[t], tri[t + 1], tri[t + 2]], t);
      if (copies === 2) index.set([n + tri[t], n + tri[t + 2], n + tri[t + 1]], tri.length + t);
    }
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(pos, 3));
    g.setAttribute("color", new THREE.BufferAttribute(col, 3));
    g.setIndex(new THREE.BufferAttribute(index, 1));
    g.computeVertexNormals();
    return g;
  }

  const container = document.getElementById("view");
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(container.clientWidth, container.clientHeight);
  renderer.setClearColor(BACKGROUND);
  container.appendChild(renderer.domElement);

  const scene = new THREE.Scene();
  scene.add(new THREE.AmbientLight(0xffffff, 0.45));
  const camera = new THREE.PerspectiveCamera(35, container.clientWidth / container.clientHeight,
                                             1, 5000);
  camera.up.set(0, 0, 1); // the model's z points up
  const headlight = new THREE.DirectionalLight(0xffffff, 0.65);
  camera.add(headlight);
  headlight.position.set(1, 1, 0.6); // from the upper right of the viewer
  scene.add(camera);

  // Frame every surface of every set: fixed camera target, so toggles show motion.
  const box = new THREE.Box3();
  for (const s of data.sets)
    for (const surf of s.surfaces) {
      const g = fullGeometry(surf, "vertices", null);
      g.computeBoundingBox();
      box.union(g.boundingBox);
      g.dispose();
    }
  const centre = box.getCenter(new THREE.Vector3());
  const radius = box.getSize(new THREE.Vector3()).length() / 2;
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.target.copy(centre);
  // Oblique start: from the front, the patient's side and a little above.
  camera.position.copy(centre).add(new THREE.Vector3(2.4, 1.5, 0.5).normalize()
                                   .multiplyScalar(4.0 * radius));
  controls.update();
  controls.addEventListener("change", render);

  let mesh = null, wire = null, frames = 0;
  function currentSurface() {
    const s = data.sets[state.set];
    return s.surfaces.find(x => x.posture === state.posture) || null;
  }
  function rebuild() {
    for (const o of [mesh, wire]) if (o) { scene.remove(o); o.geometry.dispose(); }
    mesh = wire = null;
    const surf = currentSurface();
    const info = document.getElementById("info");
    if (!surf) {
      info.textContent = `no '${state.posture}' result in ${data.sets[state.set].label}`;
      render();
      return;
    }
    mesh = new THREE.Mesh(fullGeometry(surf, "vertices", state.colour),
                          new THREE.MeshLambertMaterial({ vertexColors: true,
                                                          side: THREE.DoubleSide }));
    scene.add(mesh);
    if (state.neutral) {
      wire = new THREE.Mesh(fullGeometry(surf, "vertices_ref", null),
                            new THREE.MeshBasicMaterial({ color: 0x555555, wireframe: true,
                                                          transparent: true, opacity: 0.35 }));
      scene.add(wire);
    }
    const d = surf.fields.displacement_mm;
    info.textContent = `${data.sets[state.set].label}: ${surf.posture} (theta = ${surf.theta_deg}` +
                       ` deg), max displacement ${Math.max(...d).toFixed(1)} mm`;
    const legend = document.getElementById("legend");
    legend.style.display = surf.fields[state.colour] ? "" : "none";
    document.getElementById("field").textContent = fieldLabel(state.colour);
    document.getElementById("vmax").textContent = (vmax[state.colour] || 0).toFixed(1);
    render();
  }
  function render() {
    renderer.render(scene, camera);
    frames += 1;
  }

  function buttons(id, items, isOn, choose) {
    const span = document.getElementById(id);
    span.innerHTML = "";
    for (const it of items) {
      const b = document.createElement("button");
      b.textContent = it.label;
      b.dataset.value = it.value;
      b.className = isOn(it.value) ? "on" : "";
      b.addEventListener("click", () => { choose(it.value); refreshButtons(); rebuild(); });
      span.appendChild(b);
    }
  }
  function refreshButtons() {
    const postures = [];
    for (const s of data.sets)
      for (const surf of s.surfaces)
        if (!postures.includes(surf.posture)) postures.push(surf.posture);
    buttons("postures", postures.map(p => ({ label: p, value: p })),
            v => v === state.posture, v => { state.posture = v; });
    buttons("sets", data.sets.map((s, i) => ({ label: s.label, value: String(i) })),
            v => Number(v) === state.set, v => { state.set = Number(v); });
    buttons("colours", Object.keys(vmax).map(f => ({ label: fieldLabel(f), value: f }))
                         .concat([{ label: "skin", value: "skin" }]),
            v => v === state.colour, v => { state.colour = v; });
  }
  document.getElementById("set-row").style.display = data.sets.length > 1 ? "" : "none";
  document.getElementById("neutral").addEventListener("change", e => {
    state.neutral = e.target.checked;
    rebuild();
  });

  const bar = document.getElementById("bar").getContext("2d");
  for (let x = 0; x < 200; ++x) {
    const [r, g, b] = colormap(x / 199);
    bar.fillStyle = `rgb(${255 * r},${255 * g},${255 * b})`;
    bar.fillRect(x, 0, 1, 12);
  }

  window.addEventListener("resize", () => {
    camera.aspect = container.clientWidth / container.clientHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(container.clientWidth, container.clientHeight);
    render();
  });

  refreshButtons();
  rebuild();
  // For tests: the drawn surface's vertex and triangle counts and the
  // current surface's own (a mirrored half draws twice its own).
  function drawn() {
    const surf = currentSurface(), g = mesh && mesh.geometry;
    return { mirrored: surf ? mirrored(surf) : null,
             vertices: g ? g.getAttribute("position").count : 0,
             triangles: g ? g.index.count / 3 : 0,
             surfaceVertices: surf ? surf.vertices.length / 3 : 0,
             surfaceTriangles: surf ? surf.triangles.length / 3 : 0,
             xRange: g ? (g.computeBoundingBox(), [g.boundingBox.min.x, g.boundingBox.max.x]) : null };
  }
  window.breastsimViewer = { ready: true, state, frames: () => frames, drawn };
})();
