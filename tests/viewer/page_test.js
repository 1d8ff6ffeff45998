// SPDX-License-Identifier: LGPL-3.0-or-later
// The 3D page in a real headless Chromium (Debian's chromium, driven by
// playwright-core): loads from file:// without console errors or network
// requests, the WebGL canvas draws non-background pixels, and the posture
// and pre/post toggles, the colouring and a mouse drag change the picture.
// The page draws a half model (mirror_x) with its mirror image (twice its
// vertices and triangles) and a full breast as it is; MODEL half|full says
// which the first surface must be (a full breast: x of both signs drawn).
// Usage: node page_test.js INDEX_HTML [half|full]   (NODE_PATH must reach
// playwright-core; BREASTSIM_SCREENSHOT=FILE.png saves the first view)
"use strict";
const fs = require("fs");
const os = require("os");
const path = require("path");
const { chromium } = require("playwright-core");

const CHROMIUM = process.env.BREASTSIM_CHROMIUM || "/usr/bin/chromium";
const page_file = path.resolve(process.argv[2]);
const model = process.argv[3] || "half";
if (!["half", "full"].includes(model)) {
  console.error(`MODEL must be 'half' or 'full' (got '${model}')`);
  process.exit(2);
}
let passed = 0;

function check(ok, what) {
  if (!ok) throw new Error("FAILED: " + what);
  console.log("ok: " + what);
  passed += 1;
}

// Snapshot the canvas pixels inside the page (read back through a 2D canvas)
// under `name`; returns the fraction of pixels that differ from the
// background (the top-left pixel). Pixels stay in the page: fast.
async function snapshot(page, name) {
  return page.evaluate((name) => {
    const gl = document.querySelector("#view canvas");
    const c = document.createElement("canvas");
    c.width = gl.width;
    c.height = gl.height;
    const ctx = c.getContext("2d");
    ctx.drawImage(gl, 0, 0);
    const px = ctx.getImageData(0, 0, c.width, c.height).data;
    (window.__snapshots = window.__snapshots || {})[name] = px;
    let drawn = 0;
    for (let i = 0; i < px.length; i += 4)
      if (Math.abs(px[i] - px[0]) + Math.abs(px[i + 1] - px[1]) + Math.abs(px[i + 2] - px[2]) > 12)
        drawn += 1;
    return drawn / (px.length / 4);
  }, name);
}

// Fraction of pixels that differ between two snapshots.
async function difference(page, a, b) {
  return page.evaluate(([a, b]) => {
    const p = window.__snapshots[a], q = window.__snapshots[b];
    let diff = 0;
    for (let i = 0; i < p.length; i += 4)
      if (Math.abs(p[i] - q[i]) + Math.abs(p[i + 1] - q[i + 1]) + Math.abs(p[i + 2] - q[i + 2]) > 12)
        diff += 1;
    return diff / (p.length / 4);
  }, [a, b]);
}

async function main() {
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), "breastsim-chromium-"));
  // A fresh profile folder (playwright passes it as --user-data-dir).
  const browser = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    viewport: { width: 640, height: 480 },
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync",
           "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
  });
  try {
    const page = await browser.newPage();
    const errors = [], requests = [];
    page.on("console", m => { if (m.type() === "error") errors.push(m.text()); });
    page.on("pageerror", e => errors.push(String(e)));
    page.on("request", r => { if (!r.url().startsWith("file://")) requests.push(r.url()); });

    await page.goto("file://" + page_file);
    await page.waitForFunction(() => window.breastsimViewer && window.breastsimViewer.ready,
                               null, { timeout: 30000 });
    check(errors.length === 0, "no console errors on load" + (errors.length ? ": " + errors : ""));
    check(requests.length === 0, "no network requests" + (requests.length ? ": " + requests : ""));

    if (process.env.BREASTSIM_SCREENSHOT) await page.screenshot({ path: process.env.BREASTSIM_SCREENSHOT });
    const geometry = await page.evaluate(() => window.breastsimViewer.drawn());
    const copies = model === "half" ? 2 : 1;
    check(geometry.mirrored === (model === "half") &&
          geometry.vertices === copies * geometry.surfaceVertices &&
          geometry.triangles === copies * geometry.surfaceTriangles,
          `a ${model} model is drawn ${model === "half" ? "with its mirror image" : "as it is"} ` +
          `(${geometry.vertices} vertices, ${geometry.triangles} triangles of the surface's ` +
          `${geometry.surfaceVertices}, ${geometry.surfaceTriangles})`);
    const [xmin, xmax] = geometry.xRange;
    check(xmin < -10 && xmax > 10 && (model === "full" || Math.abs(xmin + xmax) < 1e-3),
          `the drawn breast spans x = ${xmin.toFixed(1)} to ${xmax.toFixed(1)} mm` +
          (model === "half" ? " (symmetric)" : ""));
    const drawn = await snapshot(page, "standing");
    check(drawn > 0.03, `canvas draws the breast (${(100 * drawn).toFixed(1)} % non-background)`);

    await page.click('#postures button[data-value="supine"]');
    await snapshot(page, "supine");
    const d1 = await difference(page, "standing", "supine");
    check(d1 > 0.005, `posture toggle changes the picture (${(100 * d1).toFixed(1)} % pixels)`);
    await page.click('#postures button[data-value="standing"]');

    const sets = await page.$$("#sets button");
    if (sets.length > 1) {
      await snapshot(page, "first set");
      await sets[1].click();
      await snapshot(page, "second set");
      const d2 = await difference(page, "first set", "second set");
      check(d2 > 0.005, `pre/post toggle changes the picture (${(100 * d2).toFixed(1)} % pixels)`);
    }

    await snapshot(page, "coloured");
    await page.click('#colours button[data-value="skin"]');
    await snapshot(page, "skin");
    check(await difference(page, "coloured", "skin") > 0.005, "colour toggle changes the picture");

    // Rotate by dragging: the view changes.
    await snapshot(page, "before drag");
    await page.mouse.move(320, 240);
    await page.mouse.down();
    await page.mouse.move(420, 260, { steps: 5 });
    await page.mouse.up();
    await snapshot(page, "after drag");
    check(await difference(page, "before drag", "after drag") > 0.005, "dragging rotates the view");
    check(errors.length === 0, "no console errors after interaction" + (errors.length ? ": " + errors : ""));
  } finally {
    await browser.close();
    fs.rmSync(profile, { recursive: true, force: true });
  }
  console.log(`${passed} passed, 0 failed`);
}

main().catch(e => { console.error(e.message || e); process.exit(1); });
