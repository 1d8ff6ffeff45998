// SPDX-License-Identifier: LGPL-3.0-or-later
// The planning app's page: patient measurements -> plan (a, s, h, d) ->
// surgery job -> pre/post numbers and view -> compare -> export, over the
// JSON API of `breastsim serve` (docs/APP.md). Every value is checked by the
// server with the library's messages; the page only adds checks as typed.
import { View3D, POINT_COLOURS } from "/view3d.js";
import { reportPictures, usesFit } from "/report.js";
import { SWEEP_KEYS, sweepPictures, sweepRequest, sweepTable } from "/sweep.js";
import { evaluationStage, misfitCaption, misfitPlotSvg } from "/misfit_plot.js";
import { TIPS, attachScan, buildConsultForms, fillPatient, goalTargets, patientDocument, patientTable, planTables } from "/consult.js";
import { RECORDING_FORMAT, SCAN_LIMITS, recordingText, scanSummaryHtml, scanUploadPath, uploadScan } from "/patient_files.js";

const $ = (s) => document.querySelector(s);
const state = { keys: {}, job: null, incisionOk: false, measurements: null, recording: null, scan: null, surfaces: {},
                evaluations: { id: null, list: [] } };
const app = (window.breastsimApp = { ready: false, lastRedrawMs: null, redraws: 0, reports: 0, sweeps: 0, errors: [] });
let view;

async function api(method, path, body) {
  const opts = { method, headers: {} };
  if (body !== undefined) {
    opts.headers["Content-Type"] = "application/json";
    opts.body = JSON.stringify(body);
  }
  const r = await fetch(path, opts);
  const text = await r.text();
  let json = null;
  try { json = JSON.parse(text); } catch (e) { json = { text }; }
  return { status: r.status, json };
}

function message(el, text, good) {
  el.textContent = text || "";
  el.className = "message " + (text ? (good ? "good" : "bad") : "");
}

function debounce(fn, ms) {
  let t = null;
  return (...a) => { clearTimeout(t); t = setTimeout(() => fn(...a), ms); };
}

// ---- Breast model (case keys; lengths shown in mm) ----
const CASE_FIELDS = [
  ["geometry.R", "base radius R", 1e3, "mm"], ["geometry.H", "height H", 1e3, "mm"],
  ["geometry.mesh_size", "mesh size", 1e3, "mm"], ["tissue.rho", "tissue density", 1, "kg/m³"],
  ["tissue.mu", "tissue shear modulus", 1, "Pa"], ["skin.mu", "skin shear modulus", 1, "Pa"],
];

function numberField(parent, id, label, value, unit) {
  const d = document.createElement("div");
  d.className = "field";
  d.innerHTML = `<label for="${id}">${label} [${unit}]</label><input type="number" step="any" id="${id}">`;
  parent.appendChild(d);
  const input = d.querySelector("input");
  if (value !== null && value !== undefined) input.value = value;
  return input;
}

// Range check of one case key as typed (the schema's bounds), in display units.
function keyProblem(key, scale, text) {
  const k = state.keys[key], v = Number(text) / scale;
  if (text === "" || !Number.isFinite(v)) return `${key}: enter a number`;
  const loOk = k.lo === null || (k.lo_open ? v > k.lo : v >= k.lo);
  const hiOk = k.hi === null || (k.hi_open ? v < k.hi : v <= k.hi);
  return loOk && hiOk ? "" : `key '${key}' = ${v} is out of range: allowed ${k.allowed} ${k.unit}`;
}

function buildCaseFields() {
  const box = $("#case-fields");
  for (const [key, label, scale, unit] of CASE_FIELDS) {
    const input = numberField(box, "case-" + key.replace(".", "-"), label, +(state.keys[key].default * scale).toPrecision(6), unit);
    input.dataset.key = key;
    input.dataset.scale = scale;
    input.addEventListener("input", () => {
      const p = keyProblem(key, scale, input.value);
      input.classList.toggle("bad", !!p);
      message($("#case-message"), p);
      if (!p) validateCase();
    });
  }
  const posts = document.createElement("div");
  posts.className = "field";
  posts.innerHTML = "<label>postures</label>" + ["standing", "supine", "all_fours"].map((p) =>
    `<label style="display:inline"><input type="checkbox" class="posture" value="${p}" checked> ${p}</label>`).join(" ");
  box.appendChild(posts);
  posts.addEventListener("change", () => validateCase());
}

function caseOverrides() {
  const o = { ...(state.extraOverrides || {}) };
  for (const input of document.querySelectorAll("#case-fields input[type=number]"))
    o[input.dataset.key] = Number(input.value) / Number(input.dataset.scale);
  o["postures.names"] = [...document.querySelectorAll("#case-fields .posture:checked")].map((c) => c.value);
  for (const [key, , scale] of SLIDERS) o[key] = Number($("#slider-" + key.split(".")[1]).value) / scale;
  return o;
}

// Show a job's case on the page (a reattached job, a plan picked for
// comparison: `whole`, its keys without a field on the page replace the kept
// ones, such as a fitted base.c) or some of its keys (fitted values, a sweep's cell).
function applyOverrides(o, whole) {
  const onPage = new Set([...CASE_FIELDS, ...SLIDERS].map(([key]) => key).concat(["postures.names"]));
  const extra = Object.fromEntries(Object.entries(o).filter(([key]) => !onPage.has(key)));
  state.extraOverrides = whole ? extra : { ...state.extraOverrides, ...extra };
  for (const input of document.querySelectorAll("#case-fields input[type=number]"))
    if (o[input.dataset.key] !== undefined) input.value = +(o[input.dataset.key] * Number(input.dataset.scale)).toPrecision(6);
  if (o["postures.names"])
    for (const c of document.querySelectorAll("#case-fields .posture")) c.checked = o["postures.names"].includes(c.value);
  updateSliderRanges();
  for (const [key, , scale] of SLIDERS)
    if (o[key] !== undefined) $("#slider-" + key.split(".")[1]).value = o[key] * scale;
  showSliderValues();
}

const validateCase = debounce(async () => {
  const r = await api("POST", "/api/validate", caseOverrides());
  message($("#case-message"), r.status === 200 ? "" : r.json.error);
  updateSliderRanges();
  checkIncision();
}, 150);

// ---- Patient measurements (mm on the page, m in the document) ----
const POSTURES = ["standing", "supine", "all_fours"];
const MEASURED = ["projection", "nipple_y", "nipple_z", "z_min", "base_perimeter"];

function buildMeasurementForm() {
  const common = $("#measure-common");
  numberField(common, "m-base_perimeter", "base perimeter (standing)", null, "mm");
  numberField(common, "m-breast_height", "breast height (standing)", null, "mm");
  numberField(common, "m-sigma", "measurement error σ", 1, "mm");
  const body = $("#measure-postures tbody");
  for (const p of POSTURES) {
    const tr = document.createElement("tr");
    tr.innerHTML = `<td>${p}</td>` + MEASURED.map((q) =>
      `<td><input type="number" step="any" id="m-${p}-${q}" aria-label="${p} ${q} [mm]"></td>`).join("");
    body.appendChild(tr);
  }
  for (const input of document.querySelectorAll("#patient input[id^=m-]"))
    input.addEventListener("input", () => measurementTyped(input));
  $("#measure-file").addEventListener("change", loadMeasurementFile);
}

// Checks as typed: a number of at most 1000 mm (larger is not a breast), positive
// where a length or perimeter is meant.
function measurementProblem(input) {
  if (input.value === "") return "";
  const v = Number(input.value), name = input.id.slice(2);
  if (!Number.isFinite(v)) return `${name}: enter a number in mm`;
  if (Math.abs(v) > 1000) return `${name} = ${v} mm is out of range: |value| <= 1000 mm`;
  if (/perimeter|height|sigma|projection/.test(name) && !(v > 0)) return `${name} = ${v} mm must be > 0`;
  return "";
}

function measurementTyped(input) {
  state.recording = null; // the form's measurements again
  const p = measurementProblem(input);
  input.classList.toggle("bad", !!p);
  message($("#measure-message"), p);
  if (!p) checkMeasurements();
}

function measurementDocument() {
  const mm = (id) => { const v = $("#" + id).value; return v === "" ? undefined : Number(v) / 1e3; };
  const doc = { units: "SI", sigma: mm("m-sigma"), postures: [] };
  for (const k of ["base_perimeter", "breast_height"]) if (mm("m-" + k) !== undefined) doc[k] = mm("m-" + k);
  for (const p of POSTURES) {
    const e = { name: p };
    if (mm(`m-${p}-projection`) !== undefined) e.projection = mm(`m-${p}-projection`);
    if (mm(`m-${p}-z_min`) !== undefined) e.z_min = mm(`m-${p}-z_min`);
    if (mm(`m-${p}-base_perimeter`) !== undefined) e.base_perimeter = mm(`m-${p}-base_perimeter`);
    if (mm(`m-${p}-nipple_y`) !== undefined && mm(`m-${p}-nipple_z`) !== undefined)
      e.nipple = [0, mm(`m-${p}-nipple_y`), mm(`m-${p}-nipple_z`)];
    if (Object.keys(e).length > 1) doc.postures.push(e);
  }
  return doc;
}

const checkMeasurements = debounce(async () => {
  const doc = measurementDocument();
  if (doc.postures.length === 0) return message($("#measure-message"), "");
  const r = await api("POST", "/api/measurements/check", doc);
  state.measurements = r.status === 200 ? doc : null;
  $("#cal-run").disabled = !canRun("calibrate");
  message($("#measure-message"), r.status === 200
    ? `${r.json.measurements.length} measurements in ${r.json.postures.join(", ")}: accepted` : r.json.error, r.status === 200);
}, 200);

function loadMeasurementFile(ev) {
  const file = ev.target.files[0];
  if (!file) return;
  file.text().then((text) => {
    let doc;
    try { doc = JSON.parse(text); } catch (e) { return message($("#measure-message"), `${file.name}: not JSON`); }
    if (doc && doc.format === RECORDING_FORMAT) return loadRecording(doc, file.name);
    const set = (id, m) => { if (typeof m === "number") $("#" + id).value = +(1e3 * m).toPrecision(6); };
    set("m-base_perimeter", doc.base_perimeter);
    set("m-breast_height", doc.breast_height);
    set("m-sigma", doc.sigma);
    for (const e of doc.postures || []) {
      if (!POSTURES.includes(e.name)) continue;
      for (const q of ["projection", "z_min", "base_perimeter"]) set(`m-${e.name}-${q}`, e[q]);
      if (Array.isArray(e.nipple)) { set(`m-${e.name}-nipple_y`, e.nipple[1]); set(`m-${e.name}-nipple_z`, e.nipple[2]); }
    }
    for (const input of document.querySelectorAll("#patient input[id^=m-]"))
      input.classList.toggle("bad", !!measurementProblem(input));
    checkMeasurements();
  });
}

// A 3D surface recording: checked by the server; the calibration then fits its points.
async function loadRecording(doc, name) {
  const r = await api("POST", "/api/recording/check", doc), ok = r.status === 200 && r.json.ok;
  state.recording = ok ? doc : null;
  $("#cal-run").disabled = !canRun("calibrate");
  message($("#measure-message"), ok ? recordingText(name, r.json) : `${name}: ${r.json.error}`, ok);
}

// A skin scan: uploaded with its unit and posture; the server checks it and queues its scan job.
async function loadScan(ev) {
  const file = ev.target.files[0];
  if (!file) return;
  message($("#scan-message"), `uploading ${file.name} ...`, true);
  const r = await uploadScan(file, scanUploadPath(file, $("#scan-units").value, $("#scan-posture").value, $("#scan-mesh").value));
  ev.target.value = "";
  if (r.status !== 202) return message($("#scan-message"), `${file.name}: ${r.json.error}`);
  message($("#scan-message"), `${file.name}: accepted, building the model`, true);
  attach("scan", r.json.id, true);
}

function showScan(job) {
  state.scan = job;
  message($("#scan-message"), `the scanned breast's model is ready (job ${job.id.slice(0, 6)})`, true);
  $("#scan-result").innerHTML = scanSummaryHtml(job);
  for (const id of ["#plan-scan-note", "#simulate-scan-note"]) {
    $(id).textContent = SCAN_LIMITS;
    $(id).hidden = false;
  }
  $("#surgery-on-scan-label").hidden = false;
  $("#surgery-on-scan").checked = true;
  $("#run").disabled = !canRun("surgery");
  $("#view-mode").value = "scan";
  $("#view-posture").innerHTML = job.summary.postures.map((p) => `<option>${p.posture}</option>`).join("");
  $("#view-posture").value = job.options.scan.posture;
  view.framed = null;
  return showSurfaces();
}

// ---- Plan: sliders for a, s, h, d; points and planes drawn as they move ----
const SLIDERS = [["incision.a_deg", "a (angle of P1)", 1, "deg"], ["incision.s", "s (new nipple height)", 1e3, "mm"],
                 ["incision.h", "h (height of D)", 1e3, "mm"], ["incision.d", "d (depth of C)", 1e3, "mm"]];

function buildSliders() {
  const box = $("#sliders");
  for (const [key, label, scale, unit] of SLIDERS) {
    const name = key.split(".")[1];
    const row = document.createElement("div");
    row.className = "slider";
    row.innerHTML = `<label for="slider-${name}">${label}</label><input type="range" id="slider-${name}" step="0.5">` +
                    `<output id="value-${name}"></output>`;
    box.appendChild(row);
    const input = row.querySelector("input");
    input.value = state.keys[key].default * scale;
    input.dataset.unit = unit;
    input.addEventListener("input", () => { state.inputAt = performance.now(); showSliderValues(); checkIncision(); });
  }
  updateSliderRanges();
  showSliderValues();
}

function updateSliderRanges() {
  const R = Number($("#case-geometry-R").value), H = Number($("#case-geometry-H").value);
  const ranges = { a_deg: [0.5, 89.5], s: [0, R], h: [0.5, H], d: [0, R] };
  for (const [name, [lo, hi]] of Object.entries(ranges)) {
    const s = $("#slider-" + name);
    s.min = lo;
    s.max = hi;
  }
}

function showSliderValues() {
  for (const [key] of SLIDERS) {
    const name = key.split(".")[1], s = $("#slider-" + name);
    $("#value-" + name).textContent = `${Number(s.value).toFixed(1)} ${s.dataset.unit}`;
  }
}

// Timings as performance entries: "breastsim:first-view" (the page's panels and
// the plan, or in the surgeon's view the torso, drawn), "breastsim:slider-redraw" (a slider's input -> the frame
// with its planes).
function redrawn(inputAt) {
  app.redraws += 1;
  if (inputAt) app.lastRedrawMs = performance.measure("breastsim:slider-redraw", { start: inputAt }).duration;
  markFirstView();
}

function markFirstView() {
  if (performance.getEntriesByName("breastsim:first-view").length === 0) performance.mark("breastsim:first-view");
}

let checking = false, recheck = false;
async function checkIncision() {
  if (checking) { recheck = true; return; }
  checking = true;
  const r = await api("POST", "/api/incision/check", caseOverrides());
  state.incisionOk = r.status === 200 && r.json.ok;
  const R = Number($("#case-geometry-R").value) / 1e3, H = Number($("#case-geometry-H").value) / 1e3;
  if (state.incisionOk) {
    message($("#plan-message"), "");
    $("#points tbody").innerHTML = ["A", "B", "C", "D"].map((p) =>
      `<tr><td style="color:#${POINT_COLOURS[p].toString(16).padStart(6, "0")}">● ${p}</td>` +
      r.json[p].map((x) => `<td>${(1e3 * x).toFixed(1)}</td>`).join("") + "</tr>").join("");
  } else {
    message($("#plan-message"), "impossible: " + r.json.error);
    $("#points tbody").innerHTML = "";
  }
  $("#run").disabled = !canRun("surgery");
  $("#sweep-run").disabled = !canRun("sweep");
  if ($("#view-mode").value === "plan" && R > 0 && H > 0) {
    view.showPlan({ R, H }, state.incisionOk ? r.json : null);
    const inputAt = state.inputAt;
    state.inputAt = null;
    // The next frame shows the plan; the one after it begins once that one is out.
    requestAnimationFrame(() => requestAnimationFrame(() => redrawn(inputAt)));
  }
  checking = false;
  if (recheck) { recheck = false; checkIncision(); }
}

// ---- Jobs: a surgery or a calibration, its progress, its result ----
// One panel per kind of job; a reload reattaches each to its job.
const PANELS = {
  surgery: { run: "#run", cancel: "#cancel", progress: "#progress", stage: "#stage", message: "#job-message" },
  calibrate: { run: "#cal-run", cancel: "#cal-cancel", progress: "#cal-progress", stage: "#cal-stage",
               message: "#cal-message" },
  sweep: { run: "#sweep-run", cancel: "#sweep-cancel", progress: "#sweep-progress", stage: "#sweep-stage",
           message: "#sweep-message" },
  scan: { run: "#scan-file", cancel: "#scan-cancel", progress: "#scan-progress", stage: "#scan-stage",
          message: "#scan-message" },
  patient: { run: "#model-run", cancel: "#model-cancel", progress: "#model-progress", stage: "#model-stage",
             message: "#model-message" },
  plan: { run: "#goal-run", cancel: "#goal-cancel", progress: "#goal-progress", stage: "#goal-stage",
          message: "#goal-message" },
};
const jobs = { surgery: null, calibrate: null, sweep: null, scan: null, patient: null, plan: null };

function canRun(kind) {
  if (kind === "scan" || kind === "patient") return jobs[kind] === null;
  if (kind === "plan") return jobs.plan === null && state.patientModel !== undefined;
  if (kind === "surgery" && surgeryOnScan()) return jobs.surgery === null; // the job checks the plan on the scanned skin
  return jobs[kind] === null &&
    (kind === "calibrate" ? state.measurements !== null || state.recording !== null : state.incisionOk);
}

async function submit(kind, body) {
  const panel = PANELS[kind];
  const r = await api("POST", "/api/jobs", body);
  if (r.status !== 202) return message($(panel.message), r.json.error);
  message($(panel.message), "");
  attach(kind, r.json.id, true);
}

// On the scanned breast (when a scan is ready and chosen): the scan's neutral
// case with the plan (incision.*) and the postures; else the cap of the fields.
function surgeryOnScan() {
  return !!state.scan && $("#surgery-on-scan").checked;
}

function runSurgery() {
  if (!surgeryOnScan()) return submit("surgery", { kind: "surgery", overrides: caseOverrides() });
  const overrides = {};
  for (const [k, v] of Object.entries(caseOverrides()))
    if (k.startsWith("incision.") || k === "postures.names") overrides[k] = v;
  submit("surgery", { kind: "surgery", scan: state.scan.id, overrides });
}

function runCalibration() {
  const overrides = caseOverrides();
  for (const k of Object.keys(overrides)) if (k.startsWith("incision.")) delete overrides[k];
  const data = state.recording ? { recording: state.recording } : { measurements: state.measurements };
  submit("calibrate", { kind: "calibrate", overrides, ...data,
                        fit: $("#cal-fit").value, max_evals: Number($("#cal-evals").value) });
}

// The consultation: the landmarks of both breasts (a patient job), then the goals (a plan job).
function modelPatient() {
  state.patient = patientDocument($);
  state.tolerance = Number($("#model-tolerance").value);
  submit("patient", { kind: "patient", overrides: caseOverrides(), patient: state.patient, tolerance_mm: state.tolerance });
}

function findPlans() {
  submit("plan", { kind: "plan", overrides: caseOverrides(), patient: state.patient, targets: goalTargets($),
                   symmetric: $("#goal-symmetric").checked, tolerance_mm: state.tolerance || 1 });
}

// The expert view: the model's own steps (1-6) and terms; off by default.
function setExpert(on) {
  document.body.classList.toggle("expert", on);
  $("#expert").checked = on;
  localStorage.setItem("breastsim.expert", on ? "1" : "");
  const mode = $("#view-mode");
  if (!on && mode.selectedOptions[0].classList.contains("expert-only")) mode.value = "torso-both";
  else if (on && !state.planJob && mode.value.startsWith("torso")) mode.value = "plan";
  else return;
  view.framed = null;
  showSurfaces();
}

function showPatientModel(job) {
  state.patientModel = job.summary.patient_model;
  state.tolerance = state.patientModel.tolerance_mm;
  state.patient = job.request_patient || state.patient;
  $("#model-result").innerHTML = patientTable(state.patientModel);
  $("#goal-run").disabled = !canRun("plan");
}

// Both breasts of the last plan job on the chest, standing, before and/or after.
async function showTorso(mode) {
  const plan = state.planJob;
  if (!plan) {
    view.clear();
    view.render();
    markFirstView();
    return void ($("#view-legend").textContent = "both breasts: find the plans in the Consultation first");
  }
  const file = async (name) => {
    const r = await fetch(`/api/jobs/${plan.id}/files/${name}`);
    return r.ok ? r.json() : null;
  };
  const breasts = [];
  for (const side of plan.summary.plan.sides) {
    const model = plan.summary.patient_model.sides.find((x) => x.side === side.side);
    if (!side.plan.ok) continue;
    breasts.push({ side: side.side, notch: model.notch_m,
                   pre: await file(`${side.side}_preop_surface_standing.json`),
                   post: await file(`${side.side}_postop_surface_standing.json`),
                   nipples: { pre: model.nipple_standing_m, post: side.plan.post_standing.nipple_m },
                   drawing: side.drawing });
  }
  view.showTorso(breasts, mode, $("#view-tapes").checked);
  const scanned = breasts.filter((b) => b.drawing && b.drawing.scan).map((b) => b.side);
  if (scanned.length && mode !== "after")
    $("#view-legend").textContent += `; before surgery the ${scanned.join(" and ")} breast is its scan`;
  state.torso = { breasts };
  app.torsoShown = { mode, breasts: breasts.length, vertices: view.drawnVertices(), linked: !!view.split,
                     drawings: breasts.filter((b) => b.drawing).length,
                     scans: breasts.filter((b) => b.drawing && b.drawing.scan).length };
}

// The consultation's report: pictures of both breasts before | after (front
// and side) from the 3D view, and the plan job's numbers (written by the server).
async function consultReport() {
  const job = state.planJob;
  if (!job) return;
  $("#consult-report").disabled = true;
  $("#view-mode").value = "torso-both";
  await showSurfaces();
  const front = view.snapshot(900, 560, [0, 0.1, 1]);
  const pictures = [{ caption: "both breasts standing, from the front: before (left) | after (right)", png: front }];
  for (const breast of state.torso.breasts) { // each breast alone from its own side, before and after overlaid
    view.showTorso([breast], "overlay", false);
    pictures.push({ caption: `the ${breast.side} breast standing, from its side: before (translucent), after (blue)`,
                    png: view.snapshot(600, 560, [breast.side === "left" ? 1 : -1, 0.05, 0.15], 0.3) });
  }
  await showSurfaces();
  const r = await api("POST", `/api/jobs/${job.id}/report`, { pictures });
  $("#consult-report").disabled = false;
  if (r.status !== 200) return message($("#consult-report-message"), r.json.error);
  message($("#consult-report-message"), "");
  $("#consult-report-links").innerHTML = `<a id="consult-report-open" href="${r.json.url}" target="_blank">open the report</a>` +
    ` (print it, or save it as PDF)`;
}

function showPlans(job) {
  state.planJob = job;
  $("#consult-report").disabled = false;
  $("#view-mode").value = "torso-both";
  showSurfaces();
  $("#goal-result").innerHTML = planTables(job.summary);
  const unmet = job.summary.plan.sides.flatMap((s) => s.unmet.map((u) => `${s.side}: ${u}`));
  message($("#goal-message"), unmet.length ? "Not every goal can be met: " + unmet.join("; ") : "Every goal is met.",
          unmet.length === 0);
}

function loadPatientFile(ev) {
  const f = ev.target.files[0];
  if (!f) return;
  f.text().then((text) => {
    try { fillPatient($, JSON.parse(text)); message($("#model-message"), `${f.name} loaded`, true); }
    catch (e) { message($("#model-message"), `${f.name}: not a JSON patient file (${e.message})`); }
  });
}

function attach(kind, id, fromPage) {
  jobs[kind] = id;
  if (kind === "surgery") state.shownCase = !!fromPage;
  localStorage.setItem("breastsim.job." + kind, id);
  $(PANELS[kind].run).disabled = true;
  $(PANELS[kind].cancel).disabled = false;
  poll(kind);
}

// The calibration's evaluations so far (the job's progress channel): those
// after the last one shown while it runs, all of them (the report's exact
// history) once it has ended; the misfit plot redrawn from them.
function evaluationCursor(id) {
  const e = state.evaluations;
  return e.id === id && e.list.length ? e.list[e.list.length - 1].n : 0;
}

async function followEvaluations(job) {
  const e = state.evaluations, final = job.state !== "queued" && job.state !== "running";
  const cursor = evaluationCursor(job.id);
  if (e.id !== job.id) { e.id = job.id; e.list = []; }
  if (final && cursor > 0) {
    const all = await api("GET", `/api/jobs/${job.id}`);
    e.list = all.status === 200 ? all.json.evaluations || [] : e.list;
  } else e.list = e.list.concat((job.evaluations || []).filter((x) => x.n > cursor));
  if (job.options.data === "recording")
    return void ($("#cal-plot").innerHTML = '<p class="hint" id="cal-plot-caption">A recording\'s fit (the point-to-skin ' +
      "fit of the diagnosis) reports no evaluations while it runs; its result gives the distance per posture.</p>");
  $("#cal-plot").innerHTML = misfitPlotSvg(e.list, job.options.max_evals, final) +
    `<p class="hint" id="cal-plot-caption">${misfitCaption(e.list, final)}</p>`;
  app.plotted = { id: job.id, points: e.list.length, final,
                  live: final ? (app.plotted && app.plotted.id === job.id ? app.plotted.live : 0) : e.list.length };
}

async function poll(kind) {
  const id = jobs[kind], panel = PANELS[kind];
  if (!id) return;
  const r = await api("GET", `/api/jobs/${id}` + (kind === "calibrate" ? `?since=${evaluationCursor(id)}` : ""));
  if (r.status !== 200) { localStorage.removeItem("breastsim.job." + kind); jobs[kind] = null; return; }
  const job = r.json;
  if (kind === "calibrate") await followEvaluations(job);
  if (kind === "surgery" && !state.shownCase) { applyOverrides(job.overrides, true); state.shownCase = true; }
  $(panel.progress).value = job.progress;
  const fromChannel = kind === "calibrate" && job.state === "running" && evaluationStage(state.evaluations.list, job.options.max_evals);
  $(panel.stage).textContent = `${job.state}: ${fromChannel || job.stage}`;
  if (job.state === "queued" || job.state === "running") return setTimeout(() => poll(kind), 400);
  jobs[kind] = null;
  $(panel.cancel).disabled = true;
  $(panel.run).disabled = !canRun(kind);
  if (job.state === "done")
    await { surgery: showResult, calibrate: showCalibration, sweep: showSweep, scan: showScan, patient: showPatientModel,
            plan: showPlans }[kind](job);
  else message($(panel.message), `${job.state}: ${job.error}`);
  if (kind === "surgery") refreshPlans();
}

// Two of a, s, h, d, each +- its step, around the current plan.
function runSweep() {
  const chosen = [...new Set([$("#sweep-first").value, $("#sweep-second").value])].map((key) =>
    [key, Number($(key === "incision.a_deg" ? "#sweep-step-deg" : "#sweep-step-mm").value)]);
  submit("sweep", sweepRequest(caseOverrides(), chosen, state.keys));
}

async function showSweep(job) {
  $("#sweep-result").innerHTML = sweepTable(job);
  for (const td of document.querySelectorAll("#sweep-table td[data-params]"))
    td.addEventListener("click", () => { applyOverrides(JSON.parse(td.dataset.params)); checkIncision(); });
  await sweepPictures(view, async (name) => {
    const r = await api("GET", `/api/jobs/${job.id}/files/${name}`);
    return r.status === 200 ? r.json : null;
  });
  view.framed = null;
  await showSurfaces();
  app.sweeps += 1;
}

function cancel(kind) {
  if (jobs[kind]) api("POST", `/api/jobs/${jobs[kind]}/cancel`, {});
}

const g4 = (x) => (typeof x === "number" ? +x.toPrecision(4) : "–");

function showCalibration(job) {
  const s = job.summary;
  state.calibration = job;
  state.fitted = s.fitted_overrides;
  $("#cal-result").innerHTML = `<p>misfit χ² ${g4(s.chi2_before)} → <b data-key="chi2_after">${g4(s.chi2_after)}</b> ` +
    `(${s.measurements} measurements, ${s.evaluations} evaluations: ${s.stop_reason})</p>` +
    "<table><thead><tr><th>parameter</th><th>start</th><th>fitted</th><th>95 % interval</th><th>identifiability</th></tr></thead><tbody>" +
    s.parameters.map((p) => `<tr><td>${p.name} [${p.unit}]</td><td>${g4(p.initial)}</td><td data-key="fitted-${p.name}">${g4(p.fitted)}</td>` +
      `<td>${g4(p.interval_95[0])} – ${g4(p.interval_95[1])}</td><td style="text-align:left">${p.identifiability}</td></tr>`).join("") +
    "</tbody></table>" + (s.data === "recording" ? `<p id="cal-recording">Fitted to the recording's points: RMS distance ` +
      s.postures.map((p) => `${p.posture} ${p.rms_mm.toFixed(2)} mm`).join(", ") + ` (noise ${s.noise_sigma_mm} mm).</p>` : "") +
    '<button id="cal-use">Use the fitted values</button>';
  $("#cal-use").addEventListener("click", () => {
    applyOverrides(state.fitted);
    validateCase();
  });
}

const f1 = (x) => (x === undefined || x === null ? "–" : x.toFixed(1));
const share = (x) => (x === undefined ? "–" : (100 * x).toFixed(0) + " %");

async function showResult(job) {
  const s = job.summary;
  state.result = job;
  const off = (v, ideal, tol) => (Math.abs(v - ideal) <= tol ? "ideal-ok" : "ideal-off");
  const gaps = s.model === "full breast"
    ? `the scanned breast (full-breast surgery); largest gaps: keel faces ${s.max_gap_keel_mm.toFixed(4)} mm, ` +
      `P2 face to the chest ${s.max_gap_chest_mm.toFixed(4)} mm`
    : `largest suture gap ${s.max_suture_gap_mm.toFixed(3)} mm`;
  let html = `<p>Resected: <b data-key="resected_volume_cm3">${f1(s.resected_volume_cm3)}</b> cm³, ` +
    `<b data-key="resected_weight_g">${f1(s.resected_weight_g)}</b> g (ρ = ${s.tissue_rho_kg_m3} kg/m³); ` +
    `${gaps}.</p><table id="result-table"><thead><tr><th>posture</th>` +
    `<th title="The nipple's height y out of the chest and z along it, before → after [mm]">nipple y, z</th>` +
    `<th title="${TIPS.nipple_to_base}">nipple→base</th>` +
    `<th title="The breast's lowest point z, before → after [mm]">lowest z</th>` +
    `<th title="${TIPS.lower_pole}">lower pole</th></tr></thead><tbody>`;
  for (const p of s.postures) {
    const a = p.pre, b = p.post;
    html += `<tr data-posture="${p.posture}"><td>${p.posture}</td>` +
      `<td>${f1(a.nipple_mm[1])}, ${f1(a.nipple_mm[2])} → ${f1(b.nipple_mm[1])}, ${f1(b.nipple_mm[2])}</td>` +
      `<td>${f1(a.nipple_to_base_mm)} → <span class="${off(b.nipple_to_base_mm, s.ideal.nipple_to_base_mm, 5)}" ` +
      `data-key="post_nipple_to_base_mm">${f1(b.nipple_to_base_mm)}</span></td>` +
      `<td>${f1(a.z_min_mm)} → ${f1(b.z_min_mm)}</td>` +
      `<td>${share(a.lower_pole_share)} → <span class="${off(b.lower_pole_share, s.ideal.lower_pole_share, 0.05)}">` +
      `${share(b.lower_pole_share)}</span></td></tr>`;
  }
  html += `</tbody></table><p class="hint">Before → after. Ideals: nipple to base ≈ ${s.ideal.nipple_to_base_mm} mm (standing), ` +
    `lower pole ≈ ${(100 * s.ideal.lower_pole_share).toFixed(0)} % of the volume in front of the chest wall (below the nipple).</p>`;
  $("#result").innerHTML = html;
  $("#view-posture").innerHTML = s.postures.map((p) => `<option>${p.posture}</option>`).join("");
  $("#export-files").innerHTML = ["summary.json", "case.resolved.toml", "postop_index.html", "log.txt"]
    .filter((f) => job.files.includes(f))
    .map((f) => `<a href="/api/jobs/${job.id}/files/${f}" download>${f === "postop_index.html" ? "3D report" : f}</a>`)
    .concat([`<a id="export-folder" href="/api/jobs/${job.id}/result.tar" download>result folder (.tar)</a>`]).join(" · ");
  $("#view-mode").value = "side";
  $("#export-report").disabled = false;
  $("#report-links").innerHTML = "";
  await showSurfaces();
}

async function surface(name) {
  if (!state.surfaces[name]) {
    const r = await api("GET", `/api/jobs/${state.result.id}/files/${name}`);
    state.surfaces[name] = r.status === 200 ? r.json : null;
  }
  return state.surfaces[name];
}

async function showSurfaces() {
  const mode = $("#view-mode").value;
  $("#view-legend").textContent = { plan: "red: tissue removed; green: P1, P1'; violet: P2",
    side: "in profile: before (skin colour, left), after (blue, right)",
    overlay: "in profile: before (translucent), after (blue)",
    scan: "the scanned breast (full, not mirrored) simulated in the chosen posture",
    "torso-both": "standing, from the sternal notch (blue dot): before (skin colour, left view), after (blue, right view); the views turn together",
    "torso-before": "standing, before surgery, from the sternal notch (blue dot)",
    "torso-after": "standing, after surgery, from the sternal notch (blue dot)",
    "torso-overlay": "standing, before (translucent) and after (blue) overlaid" }[mode];
  $("#torso-presets").hidden = $("#tapes-label").hidden = !mode.startsWith("torso");
  // The posture of a finished surgery or scan; the torso is standing.
  $("#view-posture").parentElement.hidden = mode.startsWith("torso") || $("#view-posture").options.length === 0;
  if (mode.startsWith("torso")) return showTorso(mode.slice(6));
  if (mode === "scan") return showScanSurface();
  if (mode === "plan" || !state.result) return checkIncision();
  const p = $("#view-posture").value;
  view.showSurfaces(await surface(`preop_surface_${p}.json`), await surface(`postop_surface_${p}.json`), mode);
}

async function showScanSurface() {
  if (!state.scan) return;
  const name = `surface_${$("#view-posture").value}.json`, key = `scan:${state.scan.id}:${name}`;
  if (!state.surfaces[key]) {
    const r = await api("GET", `/api/jobs/${state.scan.id}/files/${name}`);
    state.surfaces[key] = r.status === 200 ? r.json : null;
  }
  const doc = state.surfaces[key];
  if (!doc) return;
  view.showScan(doc);
  app.scanShown = { id: state.scan.id, name, vertices: view.drawnVertices(), mirrored: doc.mirror_x !== false };
}

// ---- Compare plans, export ----
async function refreshPlans() {
  const r = await api("GET", "/api/jobs");
  if (r.status !== 200) return;
  const rows = r.json.jobs.filter((j) => j.kind === "surgery" && j.state === "done").map((j) => {
    const o = j.overrides, s = j.summary, st = s.postures[0];
    const v = (k, sc) => ((o[k] === undefined ? state.keys[k].default : o[k]) * sc).toFixed(1);
    return `<tr><td><a href="#" data-job="${j.id}">${j.id.slice(0, 6)}</a></td><td>${v("incision.a_deg", 1)}</td>` +
      `<td>${v("incision.s", 1e3)}</td><td>${v("incision.h", 1e3)}</td><td>${v("incision.d", 1e3)}</td>` +
      `<td>${f1(s.resected_volume_cm3)}</td><td>${f1(s.resected_weight_g)}</td><td>${f1(st.post.nipple_to_base_mm)}</td>` +
      `<td>${share(st.post.lower_pole_share)}</td></tr>`;
  });
  $("#plans tbody").innerHTML = rows.join("");
  for (const a of document.querySelectorAll("#plans a[data-job]"))
    a.addEventListener("click", async (ev) => {
      ev.preventDefault();
      state.surfaces = {};
      const j = await api("GET", `/api/jobs/${a.dataset.job}`);
      if (j.status === 200) { applyOverrides(j.json.overrides, true); showResult(j.json); }
    });
}

function download(name, text, type) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([text], { type }));
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

// The printable report of the shown surgery (report.js): pictures from this
// page's renderer, the numbers from the server.
async function makeReport() {
  const job = state.result;
  if (!job) return;
  $("#export-report").disabled = true;
  const pictures = await reportPictures(api, view, job, surface);
  view.framed = null;
  await showSurfaces();
  const calibration = usesFit(job, state.calibration) ? state.calibration.id : null;
  const r = await api("POST", `/api/jobs/${job.id}/report`, { pictures, calibration });
  $("#export-report").disabled = false;
  if (r.status !== 200) return message($("#export-message"), r.json.error);
  message($("#export-message"), "");
  $("#report-links").innerHTML = `<a id="report-open" href="${r.json.url}" target="_blank">open the report</a> ` +
    `(print it, or save it as PDF) · <a id="report-download" href="${r.json.url}" download="breastsim-report-${job.id}.html">download</a>`;
  app.reports += 1;
}

async function exportCase() {
  const r = await api("POST", "/api/validate", caseOverrides());
  if (r.status !== 200) return message($("#case-message"), r.json.error);
  download("case.toml", r.json.case_toml, "application/toml");
}

async function main() {
  window.addEventListener("error", (e) => app.errors.push(String(e.message)));
  view = new View3D($("#view"));
  const keys = await api("GET", "/api/keys");
  for (const k of keys.json.keys) state.keys[k.key] = k;
  buildCaseFields();
  buildMeasurementForm();
  buildSliders();
  buildConsultForms(document);
  for (const e of document.querySelectorAll("[data-tip]")) e.title = TIPS[e.dataset.tip];
  $("#patient-file").addEventListener("change", loadPatientFile);
  $("#model-run").addEventListener("click", modelPatient);
  for (const side of ["left", "right"])
    for (const id of [`#lm-${side}-scan`, `#lm-${side}-scan-units`]) $(id).addEventListener("change", () => attachScan($, side));
  $("#model-cancel").addEventListener("click", () => cancel("patient"));
  $("#goal-run").addEventListener("click", findPlans);
  $("#goal-cancel").addEventListener("click", () => cancel("plan"));
  $("#consult-report").addEventListener("click", consultReport);
  $("#run").addEventListener("click", runSurgery);
  $("#surgery-on-scan").addEventListener("change", () => { $("#run").disabled = !canRun("surgery"); });
  $("#cancel").addEventListener("click", () => cancel("surgery"));
  $("#cal-run").addEventListener("click", runCalibration);
  $("#cal-cancel").addEventListener("click", () => cancel("calibrate"));
  for (const id of ["#sweep-first", "#sweep-second"])
    $(id).innerHTML = Object.entries(SWEEP_KEYS).map(([k, [n]]) => `<option value="${k}">${n}</option>`).join("");
  $("#sweep-second").value = "incision.h";
  $("#sweep-run").addEventListener("click", runSweep);
  $("#sweep-cancel").addEventListener("click", () => cancel("sweep"));
  $("#scan-file").addEventListener("change", loadScan);
  $("#scan-cancel").addEventListener("click", () => cancel("scan"));
  $("#view-mode").addEventListener("change", showSurfaces);
  $("#view-posture").addEventListener("change", showSurfaces);
  $("#view-tapes").addEventListener("change", showSurfaces);
  $("#expert").addEventListener("change", () => setExpert($("#expert").checked));
  for (const b of document.querySelectorAll("#torso-presets button"))
    b.addEventListener("click", () => { view.preset(b.dataset.preset); app.preset = b.dataset.preset; });
  $("#torso-presets").hidden = true;
  $("#export-case").addEventListener("click", exportCase);
  $("#export-report").addEventListener("click", makeReport);
  $("#export-measurements").addEventListener("click", () =>
    download("measurements.json", JSON.stringify(measurementDocument(), null, 2), "application/json"));
  setExpert(localStorage.getItem("breastsim.expert") === "1");
  await showSurfaces();
  await refreshPlans();
  for (const kind of ["calibrate", "surgery", "sweep", "scan", "patient", "plan"]) { // a reload reattaches to the running (or finished) jobs
    const id = localStorage.getItem("breastsim.job." + kind);
    if (id) attach(kind, id, false);
  }
  $("#status").textContent = "connected";
  app.ready = true;
}

main();
