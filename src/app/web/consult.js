// SPDX-License-Identifier: LGPL-3.0-or-later
// The consultation: both breasts measured by landmarks (the clinic's
// vocabulary), a patient model per breast (a `patient` job), goals after
// surgery and the plans that meet them (a `plan` job), with a symmetry table
// before and after. Numbers are the jobs' own (docs/CLINIC.md).

const SIDES = ["left", "right"];
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
const TIPS = {
  sn_n: "Tape from the sternal notch over the breast to the nipple, standing.",
  n_imf: "Along the skin from the nipple down to the fold under the breast.",
  lower_pole: "The share of the breast's volume below the nipple's height; about 55 % looks natural.",
};

const cm = (m) => (m === undefined || m === null ? "–" : (100 * m).toFixed(1));
const mmcm = (mm) => (mm === undefined || mm === null ? "–" : (mm / 10).toFixed(1));

function tableRows(rows, cell) {
  return rows.map(([key, label, unit]) => `<tr title="${TIPS[key.replace("_mm", "")] || ""}"><td>${label}` +
    ` <span class="hint">${unit}</span></td>` + SIDES.map((s) => `<td>${cell(key, s)}</td>`).join("") + "</tr>").join("");
}

export function buildConsultForms(root) {
  root.querySelector("#landmarks tbody").innerHTML =
    tableRows(LANDMARKS, (k, s) => `<input type="number" step="0.1" id="lm-${s}-${k}">`) +
    `<tr><td>Ptosis grade</td>` + SIDES.map((s) => `<td><select id="lm-${s}-ptosis">` +
      PTOSIS.map((p, i) => `<option value="${i - 1}">${p}</option>`).join("") + "</select></td>").join("") + "</tr>";
  root.querySelector("#goals tbody").innerHTML =
    tableRows(GOALS, (k, s) => `<input type="number" step="any" id="goal-${s}-${k}">`);
}

/// The patient document (breastsim-patient/1, cm) of the filled-in sides.
export function patientDocument($) {
  const doc = { format: "breastsim-patient/1", units: "cm" };
  const id = $("#patient-id").value.trim();
  if (id) doc.id = id;
  for (const s of SIDES) {
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
  return doc;
}

export function fillPatient($, doc) {
  $("#patient-id").value = doc.id || "";
  for (const s of SIDES)
    for (const [k] of LANDMARKS) $(`#lm-${s}-${k}`).value = doc[s] && doc[s][k] !== undefined ? doc[s][k] : "";
  for (const s of SIDES) $(`#lm-${s}-ptosis`).value = doc[s] && doc[s].ptosis_grade !== undefined ? doc[s].ptosis_grade : -1;
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
  const rows = LANDMARKS.map(([k, label]) => `<tr><td>${label}</td>${SIDES.map((s) => cell(s, k + "_mm")).join("")}</tr>`);
  const grade = (s) => (bySide[s] ? `<td>${bySide[s].target.ptosis_grade ?? "–"}</td><td>${bySide[s].achieved.ptosis_grade}</td>` :
    "<td>–</td><td>–</td>");
  rows.push(`<tr><td>Ptosis grade</td>${grade("left")}${grade("right")}</tr>`);
  const fit = model.sides.map((x) => `${x.side} breast: every landmark within ${x.largest_error_mm.toFixed(1)} mm ` +
    `(accepted ${model.tolerance_mm} mm)`).join("; ");
  const notes = model.sides.flatMap((x) => x.notes.map((n) => `<li>${x.side}: ${n}</li>`)).join("");
  return `<table id="model-table"><thead><tr><th rowspan="2">cm</th><th colspan="2">left</th><th colspan="2">right</th></tr>` +
    `<tr><th>measured</th><th>model</th><th>measured</th><th>model</th></tr></thead><tbody>${rows.join("")}</tbody></table>` +
    `<p class="hint" id="model-fit">${fit}</p>` + (notes ? `<ul class="hint">${notes}</ul>` : "");
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
    html += `<p id="marking-${s}">Mark standing: new nipple at <b data-key="${s}-new-nipple">${mmcm(pl.surgical.new_nipple_sn_n_mm)}</b> cm ` +
      `from the sternal notch; vertical limb <b data-key="${s}-limb">${mmcm(pl.surgical.vertical_limb_mm)}</b> cm; ` +
      `remove <b data-key="${s}-grams">${pl.surgical.resection_g.toFixed(0)}</b> g.</p>`;
    const goal = (label, target, value, fmt, tol) => target === undefined ? "" :
      `<tr><td>${label}</td><td>${fmt(target)}</td><td>${fmt(value)}</td><td class="${Math.abs(value - target) <= tol ? "ideal-ok" : "ideal-off"}">` +
      `${Math.abs(value - target) <= tol ? "met" : "not met"}</td></tr>`;
    const t = p.targets, post = pl.post_standing;
    html += `<table id="goals-${s}"><thead><tr><th>goal</th><th>aim</th><th>result</th><th></th></tr></thead><tbody>` +
      goal("Sternal notch to nipple (cm)", t.sn_n_mm, post.sn_n_mm, mmcm, 5) +
      goal("Nipple to fold (cm)", t.n_imf_mm, post.n_imf_mm, mmcm, 5) +
      goal("Tissue removed (g)", t.resection_g, pl.surgical.resection_g, (g) => g.toFixed(0), 0.05 * (t.resection_g || 0)) +
      goal("Lower pole share (%)", t.lower_pole_share, post.lower_pole_share, (f) => (100 * f).toFixed(0), 0.03) +
      "</tbody></table>";
    for (const line of p.trade_offs || []) html += `<p class="hint">Trade-off: ${line}</p>`;
  }
  // Symmetry: before (the patient model) and after (the plans), left against right.
  const before = (s, f) => (model[s] ? f(model[s]) : undefined);
  const after = (s, f) => (plans[s] && plans[s].plan.ok ? f(plans[s].plan, model[s]) : undefined);
  const rows = [
    ["Sternal notch to nipple (cm)", (x) => x.achieved.sn_n_mm / 10, (p) => p.post_standing.sn_n_mm / 10],
    ["Nipple to fold (cm)", (x) => x.achieved.n_imf_mm / 10, (p) => p.post_standing.n_imf_mm / 10],
    ["Nipple below the notch (cm)", (x) => 100 * (x.notch_m[2] - x.nipple_standing_m[2]),
     (p, x) => 100 * (x.notch_m[2] - p.post_standing.nipple_m[2])],
    ["Breast volume (cm³)", (x) => capVolumeCm3(x), (p) => p.volume_post_cm3],
  ];
  const num = (v) => (v === undefined ? "–" : v.toFixed(1));
  html += `<h4>Symmetry</h4><table id="symmetry"><thead><tr><th></th><th>left before</th><th>right before</th>` +
    `<th>left after</th><th>right after</th><th>difference after</th></tr></thead><tbody>` +
    rows.map(([label, b, a]) => {
      const la = after("left", a), ra = after("right", a);
      return `<tr><td>${label}</td><td>${num(before("left", b))}</td><td>${num(before("right", b))}</td>` +
        `<td>${num(la)}</td><td>${num(ra)}</td><td>${la === undefined || ra === undefined ? "–" : num(Math.abs(la - ra))}</td></tr>`;
    }).join("") + "</tbody></table>";
  return html;
}
