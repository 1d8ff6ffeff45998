// SPDX-License-Identifier: LGPL-3.0-or-later
// The printable report of a finished surgery: the page renders the pictures
// (the plan on the neutral breast; before | after in profile in every
// posture; overlaid in profile and from the front in the first posture) and
// posts them with the calibration whose fitted values the plan holds; the
// server adds the numbers of the job's record and writes report.html
// (docs/APP.md, Export).

// Whether the surgery's case holds the calibration's fitted values (to the 6
// digits the page shows).
export function usesFit(surgeryJob, calibrationJob) {
  if (!calibrationJob || calibrationJob.state !== "done") return false;
  return Object.entries(calibrationJob.summary.fitted_overrides).every(([k, v]) =>
    typeof surgeryJob.overrides[k] === "number" && Math.abs(surgeryJob.overrides[k] / v - 1) <= 1e-5);
}

// Pictures of `job` from `view` (a View3D); `surface(name)` gives a skin
// surface document of the job. The view is left on the job's result.
export async function reportPictures(api, view, job, surface) {
  const W = 640, H = 480, pictures = [];
  const shot = (caption, direction) => pictures.push({ caption, png: view.snapshot(W, H, direction) });
  const inc = await api("POST", "/api/incision/check", job.overrides);
  const i = job.summary.incision, mm = (p) => p.map((x) => (1e3 * x).toFixed(1)).join(", ");
  if (inc.status === 200 && inc.json.ok) {
    view.showPlan(inc.json.cap, inc.json);
    shot(`The incision on the neutral breast: tissue removed in red, planes P1, P1' (green) and P2 (violet); ` +
         `A (${mm(i.A_m)}), C (${mm(i.C_m)}) mm`, [1, 0.35, 1.25]);
  }
  // Every posture before | after (at most 4 postures: with the plan and the
  // two overlays 7 pictures, within the server's 8).
  const skins = [];
  for (const { posture } of job.summary.postures) {
    const pre = await surface(`preop_surface_${posture}.json`), post = await surface(`postop_surface_${posture}.json`);
    if (!pre || !post) continue;
    skins.push({ posture, pre, post });
    view.showSurfaces(pre, post, "side");
    shot(`${posture}: before (left) | after (right), in profile`, [-1, 0.1, 0]);
  }
  if (skins.length === 0) return pictures;
  const { posture, pre, post } = skins[0]; // the first posture (standing when solved) overlaid
  view.showSurfaces(pre, post, "overlay");
  shot(`${posture}: before (translucent) and after overlaid, in profile`, [-1, 0.1, 0]);
  shot(`${posture}: before (translucent) and after overlaid, from the front`, [0, 0.1, 1]);
  return pictures;
}
