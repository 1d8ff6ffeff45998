// SPDX-License-Identifier: LGPL-3.0-or-later
// A small sweep around the current plan (a job of kind "sweep": the
// library's sweep() over +-1 step of two of a, s, h, d) and its table like
// the paper's Fig. 10: one row per value of the first parameter, one column
// per value of the second, in each cell the resected volume and weight, the
// standing nipple-to-base distance and the lower pole's share of the volume,
// over a picture of the post-operative shape.

export const SWEEP_KEYS = { "incision.a_deg": ["a", 1, "°"], "incision.s": ["s", 1e3, " mm"],
                            "incision.h": ["h", 1e3, " mm"], "incision.d": ["d", 1e3, " mm"] };

// The values key +- step (in display units), those outside the key's range dropped.
function around(key, value, step, info) {
  const scale = SWEEP_KEYS[key][1];
  return [value - step / scale, value, value + step / scale].filter((v) =>
    (info.lo === null || (info.lo_open ? v > info.lo : v >= info.lo)) &&
    (info.hi === null || (info.hi_open ? v < info.hi : v <= info.hi))).map((v) => +v.toPrecision(12));
}

// The job request: `overrides` the current plan, `chosen` two keys with their steps.
export function sweepRequest(overrides, chosen, keys) {
  const vary = {};
  for (const [key, step] of chosen) vary[key] = around(key, overrides[key], step, keys[key]);
  return { kind: "sweep", overrides, vary };
}

const show = (key, v) => `${SWEEP_KEYS[key][0]} = ${+(v * SWEEP_KEYS[key][1]).toFixed(1)}${SWEEP_KEYS[key][2]}`;
const esc = (t) => String(t).replace(/[&<>"']/g, (c) => `&#${c.charCodeAt(0)};`);

function cell(row, ideal, current) {
  if (!row) return "<td>–</td>";
  const params = esc(JSON.stringify(row.parameters));
  if (!row.ok) return `<td class="sweep-cell impossible" data-params="${params}">impossible: ${esc(row.error)}</td>`;
  const nb = row.nipple_to_base_mm, ok = Math.abs(nb - ideal.nipple_to_base_mm) <= 5 ? "ideal-ok" : "ideal-off";
  return `<td class="sweep-cell${current ? " current" : ""}" data-params="${params}">` +
    `<img class="sweep-shape" alt="" data-surface="${esc(row.postop_surface)}"><br>` +
    `<b data-key="resected_volume_cm3">${row.resected_volume_cm3.toFixed(1)}</b> cm³, ${row.resected_weight_g.toFixed(0)} g<br>` +
    `nipple→base <span class="${ok}" data-key="nipple_to_base_mm">${nb.toFixed(1)}</span> mm<br>` +
    `lower pole ${(100 * row.lower_pole_share).toFixed(0)} % of the volume</td>`;
}

// The table of a finished sweep job; the plan swept around is marked.
export function sweepTable(job) {
  const rows = job.summary.rows, keys = Object.keys(job.options.vary);
  const [k1, k2] = keys.length === 2 ? keys : [keys[0], null];
  const values = (k) => [...new Set(rows.map((r) => r.parameters[k]))].sort((a, b) => a - b);
  const find = (v1, v2) => rows.find((r) => r.parameters[k1] === v1 && (k2 === null || r.parameters[k2] === v2));
  const isCurrent = (v1, v2) => v1 === job.overrides[k1] && (k2 === null || v2 === job.overrides[k2]);
  const cols = k2 ? values(k2) : [null];
  let html = `<table id="sweep-table"><thead><tr><th></th>` +
    cols.map((v) => `<th>${k2 ? show(k2, v) : ""}</th>`).join("") + "</tr></thead><tbody>";
  for (const v1 of values(k1))
    html += `<tr><th>${show(k1, v1)}</th>` + cols.map((v2) => cell(find(v1, v2), job.summary.ideal, isCurrent(v1, v2))).join("") + "</tr>";
  return html + `</tbody></table><p class="hint">Sweep ${job.id.slice(0, 6)} around the plan in bold frame ` +
    "(standing, post-operative; the lower pole's share of the volume in front of the chest wall, below the nipple, ideal ≈ 55 %). Click a cell to load its plan.</p>";
}

// Each cell's picture, drawn by the page's renderer `view`: the standing skin
// after the surgery (blue) over the one before (translucent), in profile, all
// from one camera (framed on the first) so that the shapes compare.
// `getJson(name)`: a file of the sweep job, or null.
export async function sweepPictures(view, getJson) {
  const imgs = [...document.querySelectorAll("#sweep-table img[data-surface]")];
  if (imgs.length === 0) return;
  const pre = await getJson(imgs[0].dataset.surface.replace(/_postop_surface_/, "_preop_surface_"));
  let framed = false;
  for (const img of imgs) {
    const post = await getJson(img.dataset.surface);
    if (!pre || !post) continue;
    view.showSurfaces(pre, post, "overlay");
    if (!framed) view.look([-1, 0.1, 0]);
    framed = true;
    img.src = "data:image/png;base64," + view.snapshot(200, 150);
  }
}
