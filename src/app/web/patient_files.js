// SPDX-License-Identifier: LGPL-3.0-or-later
// Patient data from files (docs/APP.md, "The page", 1): a 3D surface
// recording (breastsim-recording/1, as `breastsim record` writes it),
// checked by the server as `calibrate` reads it, whose points the
// calibration then fits; and a skin scan (STL, PLY, OBJ with its unit)
// uploaded to a scan job (scan-model -> neutral-state -> simulate), whose
// summary and limits are shown here. The page's 3D view draws the scanned
// breast (view3d.js).

export const RECORDING_FORMAT = "breastsim-recording/1";

// What the page says the scanned breast cannot do yet, and why.
export const SCAN_LIMITS =
  "With the scanned breast: \"Run surgery\" (\"on the scanned breast\" ticked) runs the library's " +
  "full-breast surgery on the scan's neutral case with this plan's a, s, h, d, as breastsim surgery on that " +
  "case; the job refuses a plan the scanned skin cannot hold with the library's reason. Not yet: the plan's " +
  "preview and its check draw the incision on the parametric cap (geometry.R, H) only, not on the scanned " +
  "skin; the sweep and the calibration use the cap model (R, H) of the breast model.";

// The recording's check (POST /api/recording/check) in words.
export function recordingText(name, info) {
  const postures = info.postures.map((p) => `${p.name} (${p.points})`).join(", ");
  return `${name}: a recording of ${info.points} skin points in ${postures}, noise ${(1e3 * info.noise_sigma_m).toFixed(2)} mm: ` +
    "accepted; the calibration fits these points (point-to-skin, as breastsim calibrate RECORDING.json)";
}

// The query of POST /api/scans for a file and the chosen unit, posture and mesh size (mm on the page).
export function scanUploadPath(file, units, posture, meshMm) {
  const format = (file.name.split(".").pop() || "").toLowerCase();
  const q = new URLSearchParams({ format, units, posture });
  if (Number(meshMm) > 0) q.set("mesh_size", String(Number(meshMm) / 1e3));
  return "/api/scans?" + q.toString();
}

// Upload the scan's bytes; the answer {status, json} (202 with the job id, 4xx with the server's message).
export async function uploadScan(file, path) {
  const r = await fetch(path, { method: "POST", headers: { "Content-Type": "application/octet-stream" },
                                body: await file.arrayBuffer() });
  const text = await r.text();
  let json;
  try { json = JSON.parse(text); } catch (e) { json = { error: text }; }
  return { status: r.status, json };
}

const f1 = (x) => (typeof x === "number" ? x.toFixed(1) : "–");

// The finished scan job: the scan, its model, the neutral state, the breast in each posture.
export function scanSummaryHtml(job) {
  const s = job.summary, sc = s.scan, n = s.neutral;
  let html = `<p>Scan (${job.options.scan.units}, ${sc.posture}): <b data-key="scan-points">${sc.points}</b> points, ` +
    `${sc.triangles} triangles; fit RMS ${sc.fit_rms_mm.toFixed(2)} mm, noise ${sc.noise_rms_mm.toFixed(2)} mm; ` +
    `footprint radius ${f1(sc.footprint_radius_mm)} mm; model: ${sc.tetrahedra} tetrahedra, ` +
    `<b data-key="scan-volume">${f1(sc.volume_cm3)}</b> cm³. Neutral state: ${n.converged ? "converged" : "not converged"} ` +
    `in ${n.iterations} iterations (node mismatch ${n.mismatch_rms_mm.toExponential(1)} mm RMS).</p>` +
    '<table id="scan-table"><thead><tr><th>posture</th><th>nipple y,z</th><th>nipple→base</th><th>projection</th>' +
    "<th>lowest z</th><th>volume cm³</th><th>lower pole</th></tr></thead><tbody>";
  for (const p of s.postures) {
    const v = p.pre;
    html += `<tr data-posture="${p.posture}"><td>${p.posture}</td><td>${f1(v.nipple_mm[1])}, ${f1(v.nipple_mm[2])}</td>` +
      `<td>${f1(v.nipple_to_base_mm)}</td><td>${f1(v.projection_mm)}</td><td>${f1(v.z_min_mm)}</td>` +
      `<td>${f1(v.volume_cm3)}</td><td>${v.lower_pole_share === undefined ? "–" : (100 * v.lower_pole_share).toFixed(0) + " %"}</td></tr>`;
  }
  html += `</tbody></table><p class="hint">The scanned breast simulated in each posture from its neutral state ` +
    `(lengths in mm). <a id="scan-folder" href="/api/jobs/${job.id}/result.tar" download>result folder (.tar)</a></p>`;
  return html;
}
