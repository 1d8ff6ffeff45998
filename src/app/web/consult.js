// SPDX-License-Identifier: LGPL-3.0-or-later
// The consultation: both breasts measured by landmarks (the clinic's
// vocabulary), a patient model per breast (a `patient` job), goals after
// surgery and the plans that meet them (a `plan` job), with a symmetry table
// before and after. Numbers are the jobs' own (docs/CLINIC.md).

import { scanUploadPath, uploadScan } from "/patient_files.js";

const SIDES = ["left", "right"];
// The sides given as a standing scan: {id, name} of the upload (patient_scans.hpp).
export const scans = {};
const MEASURED_ON_SCAN = ["n_imf", "base_width", "projection"];
export const LANDMARKS = [
  ["sn_n", "Sternal notch to nipple", "cm", true], ["n_imf", "Nipple to fold", "cm", true],
  ["base_width", "Breast width", "cm", true], ["nipple_midline", "Nipple to midline", "cm", true],
  ["projection", "Projection (optional)", "cm", false],
];
export const GOALS = [
  ["sn_n_mm", "Sternal notch to nipple after", "cm", 10], ["n_imf_mm", "Nipple to fold after", "cm", 10],
  ["grams", "Tissue removed", "g", 1], ["lower_pole", "Lower pole share (optional)", "%", 0.01],
];
const PTOSIS = ["—", "0 none", "1 nipple at the fold", "2 nipple 1-3 cm below", "3 nipple lower still"];
// One definition per number, the same as docs/CLINIC.md "Definitions": shown as each row's tooltip.
export const TIPS = {
  sn_n: "Sternal notch to nipple: a taut tape from the notch at the top of the breastbone to the nipple, standing.",
  n_imf: "Nipple to fold: along the skin from the nipple straight down to the fold under the breast, standing.",
  base_width: "Breast width: the breast's footprint on the chest, from its inner to its outer edge.",
  nipple_midline: "Nipple to midline: the nipple's sideways distance from the middle of the chest (the notch's line).",
  projection: "Projection: how far the breast stands out in front of the chest wall.",
  ptosis: "Ptosis grade (Regnault) from the nipple's height against the fold: 0 more than 1 cm above it, 1 within 1 cm of it, 2 1-3 cm below, 3 more than 3 cm below.",
  volume_removed: "Tissue removed from this breast, in cm³ of its unloaded shape.",
  grams: "Tissue removed from this breast, in grams: the removed volume times the tissue's density (0.97 g/cm³ unless the case says otherwise).",
  lower_pole: "Lower pole share: the share of the breast's volume (in front of the chest) that lies below the nipple's height, standing; about 55 % looks natural.",
  new_nipple: "New nipple position, marked standing before surgery: the tape from the sternal notch to where the nipple will sit.",
  limb: "Vertical limb: the length of each vertical line of the marking, from the new nipple down, standing before surgery.",
  volume: "Breast volume: the breast's volume in front of the chest wall in its unloaded shape (as if weightless), in cm³; 1 cm³ of breast tissue weighs about 0.97 g.",
  nipple_to_base: "Nipple to base: the nipple's distance in front of the chest wall (the breast's base plane), in mm, before → after; green when within 5 mm of the ideal named below the table.",
  nipple_height: "Nipple below the notch: the nipple's height below the sternal notch, standing.",
  scan: "Standing scan (optional): a 3D surface scan of this breast taken standing (STL, PLY or OBJ, coordinates in mm or m). Nipple to fold, width, projection and ptosis grade are then measured on the scan; the sternal notch to nipple and the nipple to midline are still measured with a tape.",
  model_to_scan: "How far the model's standing skin lies from the scan's: the mean distance over the scanned skin (with both placed at the fold), and the two volumes.",
  bsa: "Body surface area from height and weight (Mosteller: the square root of height [cm] x weight [kg] / 3600); resections are weighed in grams per m² of it.",
};

const cm = (m) => (m === undefined || m === null ? "–" : (100 * m).toFixed(1));
const mmcm = (mm) => (mm === undefined || mm === null ? "–" : (mm / 10).toFixed(1));

function tableRows(rows, cell) {
  return rows.map(([key, label, unit]) => `<tr title="${TIPS[key.replace("_mm", "")] || ""}"><td>${label}` +
    ` <span class="hint">${unit}</span></td>` + SIDES.map((s) => `<td>${cell(key, s)}</td>`).join("") + "</tr>").join("");
}

export function buildConsultForms(root) {
  root.querySelector("#landmarks tbody").innerHTML =
    `<tr title="${TIPS.scan}"><td>Standing scan (optional)</td>` + SIDES.map((s) => `<td><label class="pick">` +
      `<input type="file" id="lm-${s}-scan" accept=".stl,.ply,.obj" hidden>choose…</label> ` +
      `<select id="lm-${s}-scan-units" aria-label="unit of the ${s} scan"><option value="mm">mm</option>` +
      `<option value="m">m</option></select><br><span class="hint" id="lm-${s}-scan-status"></span></td>`).join("") +
      "</tr>" +
    tableRows(LANDMARKS, (k, s) => `<input type="number" step="0.1" id="lm-${s}-${k}">`) +
    `<tr title="${TIPS.ptosis}"><td>Ptosis grade</td>` + SIDES.map((s) => `<td><select id="lm-${s}-ptosis">` +
      PTOSIS.map((p, i) => `<option value="${i - 1}">${p}</option>`).join("") + "</select></td>").join("") + "</tr>";
  root.querySelector("#goals tbody").innerHTML =
    tableRows(GOALS, (k, s) => `<input type="number" step="any" id="goal-${s}-${k}">`);
}

/// Upload side `s`'s chosen scan for the consultation: on success its
/// measurements are taken from the scan (their fields are disabled).
export async function attachScan($, s) {
  const file = $(`#lm-${s}-scan`).files[0], status = $(`#lm-${s}-scan-status`);
  delete scans[s];
  for (const k of MEASURED_ON_SCAN) $(`#lm-${s}-${k}`).disabled = false;
  $(`#lm-${s}-ptosis`).disabled = false;
  if (!file) return void (status.textContent = "");
  status.textContent = `uploading ${file.name.slice(0, 24)} ...`;
  const path = scanUploadPath(file, $(`#lm-${s}-scan-units`).value, "standing", 0) + "&use=consultation";
  const r = await uploadScan(file, path);
  if (r.status !== 202) return void (status.textContent = `${file.name.slice(0, 24)}: ${r.json.error}`);
  scans[s] = { id: r.json.id, name: file.name };
  for (const k of MEASURED_ON_SCAN) $(`#lm-${s}-${k}`).disabled = true;
  $(`#lm-${s}-ptosis`).disabled = true;
  status.textContent = `${file.name.slice(0, 24)}: measured on it`;
  status.title = "Nipple to fold, width, projection and ptosis grade will be measured on this scan.";
}

/// The patient document (breastsim-patient/1, cm) of the filled-in sides.
export function patientDocument($) {
  const doc = { format: "breastsim-patient/1", units: "cm" };
  const id = $("#patient-id").value.trim();
  if (id) doc.id = id;
  for (const s of SIDES) {
    if (scans[s]) { // measured on the scan; the tape's two as entered (null: named as missing by the server)
      const v = (k) => ($(`#lm-${s}-${k}`).value === "" ? null : Number($(`#lm-${s}-${k}`).value));
      doc[s] = { scan: { upload: scans[s].id }, sn_n: v("sn_n"), nipple_midline: v("nipple_midline") };
      continue;
    }
    const side = {};
    for (const [k, , , required] of LANDMARKS) {
      const v = $(`#lm-${s}-${k}`).value;
      if (v !== "") side[k] = Number(v);
      else if (required && Object.keys(side).length) side[k] = null; // named as missing by the server
    }
    const g = Number($(`#lm-${s}-ptosis`).value);
    if (Object.keys(side).length && g >= 0) side.ptosis_grade = g;
    if (Object.keys(side).length) doc[s] = side;
  }
  const body = {};
  if ($("#body-height").value !== "") body.height = Number($("#body-height").value);
  if ($("#body-weight").value !== "") body.weight_kg = Number($("#body-weight").value);
  if ($("#body-bra").value.trim()) body.bra_size = $("#body-bra").value.trim();
  if (Object.keys(body).length) doc.body = body;
  return doc;
}

export function fillPatient($, doc) {
  $("#patient-id").value = doc.id || "";
  for (const s of SIDES)
    for (const [k] of LANDMARKS) $(`#lm-${s}-${k}`).value = doc[s] && doc[s][k] !== undefined ? doc[s][k] : "";
  for (const s of SIDES) $(`#lm-${s}-ptosis`).value = doc[s] && doc[s].ptosis_grade !== undefined ? doc[s].ptosis_grade : -1;
  for (const s of SIDES) // a file names its scan by a path on the surgeon's machine: the page cannot open it itself
    if (doc[s] && doc[s].scan && !scans[s])
      $(`#lm-${s}-scan-status`).textContent = `the file names the scan ${String(doc[s].scan.file || "").split(/[\\/]/).pop()}: ` +
        "choose it here";
  const body = doc.body || {}, scale = { mm: 0.1, cm: 1, m: 100 }[doc.units] || 1;
  $("#body-height").value = body.height !== undefined ? body.height * scale : "";
  $("#body-weight").value = body.weight_kg !== undefined ? body.weight_kg : "";
  $("#body-bra").value = body.bra_size || "";
}

/// The body's line: height, weight, body surface area, bra size (those given).
function bodyLine(body) {
  if (!body) return "";
  const parts = [];
  if (body.bsa_m2 !== undefined) parts.push(`body surface area <span data-key="bsa">${body.bsa_m2.toFixed(2)}</span> m²`);
  if (body.height_m !== undefined) parts.push(`height ${(100 * body.height_m).toFixed(0)} cm`);
  if (body.weight_kg !== undefined) parts.push(`weight ${body.weight_kg} kg`);
  if (body.bra_size) parts.push(`bra ${body.bra_size}`);
  return parts.length ? `<p class="hint" id="model-body" title="${TIPS.bsa}">Body: ${parts.join(", ")}.</p>` : "";
}

/// The goals per side (the plan job's targets: mm, g, share).
export function goalTargets($) {
  const targets = {};
  for (const s of SIDES)
    for (const [k, , , scale] of GOALS) {
      const v = $(`#goal-${s}-${k}`).value;
      if (v !== "") (targets[s] = targets[s] || {})[k] = Number(v) * scale;
    }
  return targets;
}

export function patientTable(model) {
  const bySide = Object.fromEntries(model.sides.map((x) => [x.side, x]));
  const cell = (s, key) => {
    const x = bySide[s];
    if (!x) return "<td>–</td><td>–</td>";
    const t = x.target[key], a = x.achieved[key];
    return `<td>${t === undefined ? "–" : mmcm(t)}</td><td data-key="${s}-${key}">${mmcm(a)}</td>`;
  };
  const rows = LANDMARKS.map(([k, label]) => `<tr title="${TIPS[k]}"><td>${label}</td>${SIDES.map((s) => cell(s, k + "_mm")).join("")}</tr>`);
  const grade = (s) => (bySide[s] ? `<td>${bySide[s].target.ptosis_grade ?? "–"}</td><td>${bySide[s].achieved.ptosis_grade}</td>` :
    "<td>–</td><td>–</td>");
  rows.push(`<tr title="${TIPS.ptosis}"><td>Ptosis grade</td>${grade("left")}${grade("right")}</tr>`);
  const fit = model.sides.map((x) => `${x.side} breast: every landmark within ${x.largest_error_mm.toFixed(1)} mm ` +
    `(accepted ${model.tolerance_mm} mm)`).join("; ");
  const notes = model.sides.flatMap((x) => x.notes.map((n) => `<li>${x.side}: ${n}</li>`)).join("");
  const scanned = model.sides.filter((x) => x.scan).map((x) => `<p class="hint" id="model-scan-${x.side}" ` +
    `title="${TIPS.model_to_scan}">${x.side} breast: measured on its scan ${x.scan.file}; the model's skin lies ` +
    `<b data-key="${x.side}-scan-mean">${x.scan.model_to_scan_mm.mean.toFixed(1)}</b> mm from the scan's on average ` +
    `(95 % within ${x.scan.model_to_scan_mm.p95.toFixed(1)} mm); volume ${x.scan.volume_cm3.model.toFixed(0)} cm³ ` +
    `against the scan's ${x.scan.volume_cm3.scan.toFixed(0)} cm³.</p>`).join("");
  const expert = model.sides.map((x) => `${x.side}: cap R = ${(1e3 * x.R_m).toFixed(1)} mm, H = ${(1e3 * x.H_m).toFixed(1)} mm, ` +
    `moduli x ${x.stiffness_factor.toPrecision(3)} (tissue mu = ${x.tissue_mu_Pa.toPrecision(3)} Pa), ${x.solves} standing solves`).join("; ");
  return `<table id="model-table"><thead><tr><th rowspan="2">cm</th><th colspan="2">left</th><th colspan="2">right</th></tr>` +
    `<tr><th>measured</th><th>model</th><th>measured</th><th>model</th></tr></thead><tbody>${rows.join("")}</tbody></table>` +
    `<p class="hint" id="model-fit">${fit}</p>` + scanned + (notes ? `<ul class="hint">${notes}</ul>` : "") + bodyLine(model.body) +
    `<p class="expert-only expert-note">Model: ${expert}.</p>`;
}

function capVolumeCm3(x) { // pi H (3 R^2 + H^2) / 6, full breast
  return 1e6 * Math.PI * x.H_m * (3 * x.R_m * x.R_m + x.H_m * x.H_m) / 6;
}

export function planTables(result) {
  const model = Object.fromEntries(result.patient_model.sides.map((x) => [x.side, x]));
  const plans = Object.fromEntries(result.plan.sides.map((x) => [x.side, x]));
  let html = "";
  for (const s of SIDES) {
    const p = plans[s];
    if (!p) continue;
    const pl = p.plan;
    html += `<h4>${s} breast: Wise (inverted-T) pattern</h4>`;
    if (!pl.ok) { html += `<p class="message bad">No operable plan: ${pl.error}</p>`; continue; }
    const bsa = result.patient_model.body && result.patient_model.body.bsa_m2;
    const perArea = bsa ? ` (<span title="${TIPS.bsa}">${(pl.surgical.resection_g / bsa).toFixed(0)} g per m² of body surface</span>)` : "";
    html += `<p id="marking-${s}" title="${TIPS.new_nipple} ${TIPS.limb} ${TIPS.grams}">Mark standing: new nipple at <b data-key="${s}-new-nipple">${mmcm(pl.surgical.new_nipple_sn_n_mm)}</b> cm ` +
      `from the sternal notch; vertical limb <b data-key="${s}-limb">${mmcm(pl.surgical.vertical_limb_mm)}</b> cm; ` +
      `remove <b data-key="${s}-grams">${pl.surgical.resection_g.toFixed(0)}</b> g${perArea}.</p>` +
      `<p class="expert-only expert-note">Incision: a = ${pl.incision.a_deg.toFixed(1)} deg, s = ${(1e3 * pl.incision.s_m).toFixed(1)} mm, ` +
      `h = ${(1e3 * pl.incision.h_m).toFixed(1)} mm, d = ${(1e3 * pl.incision.d_m).toFixed(1)} mm (planes P1, P2: docs/CLINIC.md).</p>`;
    const goal = (label, target, value, fmt, tol, tip) => target === undefined ? "" :
      `<tr title="${tip}"><td>${label}</td><td>${fmt(target)}</td><td>${fmt(value)}</td><td class="${Math.abs(value - target) <= tol ? "ideal-ok" : "ideal-off"}">` +
      `${Math.abs(value - target) <= tol ? "met" : "not met"}</td></tr>`;
    const t = p.targets, post = pl.post_standing;
    html += `<table id="goals-${s}"><thead><tr><th>goal</th><th>aim</th><th>result</th><th></th></tr></thead><tbody>` +
      goal("Sternal notch to nipple (cm)", t.sn_n_mm, post.sn_n_mm, mmcm, 5, TIPS.sn_n) +
      goal("Nipple to fold (cm)", t.n_imf_mm, post.n_imf_mm, mmcm, 5, TIPS.n_imf) +
      goal("Tissue removed (g)", t.resection_g, pl.surgical.resection_g, (g) => g.toFixed(0), 0.05 * (t.resection_g || 0), TIPS.grams) +
      goal("Lower pole share (%)", t.lower_pole_share, post.lower_pole_share, (f) => (100 * f).toFixed(0), 0.03, TIPS.lower_pole) +
      "</tbody></table>";
    for (const line of p.trade_offs || []) html += `<p class="hint">Trade-off: ${line}</p>`;
  }
  // Symmetry: before (the patient model) and after (the plans), left against right.
  const before = (s, f) => (model[s] ? f(model[s]) : undefined);
  const after = (s, f) => (plans[s] && plans[s].plan.ok ? f(plans[s].plan, model[s]) : undefined);
  const rows = [
    ["Sternal notch to nipple (cm)", (x) => x.achieved.sn_n_mm / 10, (p) => p.post_standing.sn_n_mm / 10, TIPS.sn_n],
    ["Nipple to fold (cm)", (x) => x.achieved.n_imf_mm / 10, (p) => p.post_standing.n_imf_mm / 10, TIPS.n_imf],
    ["Nipple below the notch (cm)", (x) => 100 * (x.notch_m[2] - x.nipple_standing_m[2]),
     (p, x) => 100 * (x.notch_m[2] - p.post_standing.nipple_m[2]), TIPS.nipple_height],
    ["Breast volume (cm³)", (x) => capVolumeCm3(x), (p) => p.volume_post_cm3, TIPS.volume],
  ];
  const num = (v) => (v === undefined ? "–" : v.toFixed(1));
  html += `<h4>Symmetry</h4><table id="symmetry"><thead><tr><th></th><th>left before</th><th>right before</th>` +
    `<th>left after</th><th>right after</th><th>difference after</th></tr></thead><tbody>` +
    rows.map(([label, b, a, tip]) => {
      const la = after("left", a), ra = after("right", a);
      return `<tr title="${tip}"><td>${label}</td><td>${num(before("left", b))}</td><td>${num(before("right", b))}</td>` +
        `<td>${num(la)}</td><td>${num(ra)}</td><td>${la === undefined || ra === undefined ? "–" : num(Math.abs(la - ra))}</td></tr>`;
    }).join("") + "</tbody></table>";
  return html;
}
