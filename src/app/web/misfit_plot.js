// SPDX-License-Identifier: LGPL-3.0-or-later
// The misfit plot of a calibration: chi2 of every evaluation on a log
// scale against its number, drawn live from the job's progress channel
// (GET /api/jobs/<id>?since=N, `evaluations` [{n, chi2, params, best,
// stage}]) and redrawn from the report's exact history when the job ends.
// Plain SVG: one circle per evaluation (data-n, data-chi2: the API's value),
// the chi2 path and the best value so far.

const W = 440, H = 180, L = 46, R = 12, T = 12, B = 30; // view box and margins
const STAGE_COLOURS = { start: "#3b3040", fit: "#8e44ad", "corrected fit": "#d35400", uncertainty: "#95a5a6" };
const esc = (t) => String(t).replace(/[&<>"']/g, (c) => `&#${c.charCodeAt(0)};`);

// The decades [lo, hi] (integers, lo < hi) that hold every positive value of `values`.
export function decades(values) {
  const pos = values.filter((v) => typeof v === "number" && v > 0 && Number.isFinite(v));
  if (pos.length === 0) return [0, 1];
  const lo = Math.floor(Math.log10(Math.min(...pos)));
  const hi = Math.ceil(Math.log10(Math.max(...pos)));
  return [lo, hi > lo ? hi : lo + 1];
}

// About five integer ticks in [1, n].
export function evaluationTicks(n) {
  const step = [1, 2, 5, 10, 20, 25, 50, 100, 200, 250, 500, 1000].find((s) => n / s <= 6) || Math.ceil(n / 5);
  const ticks = [1];
  for (let t = step; t <= n; t += step) if (t > 1) ticks.push(t);
  return ticks;
}

// The best chi2 so far after each evaluation.
export function bestSoFar(evaluations) {
  let best = Infinity;
  return evaluations.map((e) => (best = typeof e.chi2 === "number" && e.chi2 < best ? e.chi2 : best));
}

// The plot as SVG text: `evaluations` in order, `maxEvals` the request's
// most evaluations (the x axis reaches it while the job runs), `final`
// whether the job has ended.
export function misfitPlotSvg(evaluations, maxEvals, final) {
  const last = evaluations.length ? evaluations[evaluations.length - 1].n : 0;
  const xMax = Math.max(2, last, final ? 0 : maxEvals || 0);
  const [lo, hi] = decades(evaluations.map((e) => e.chi2));
  const x = (n) => L + ((n - 1) / (xMax - 1)) * (W - L - R);
  const y = (v) => (typeof v === "number" && v > 0 ? T + ((hi - Math.log10(v)) / (hi - lo)) * (H - T - B) : T);
  let s = `<svg id="misfit-svg" viewBox="0 0 ${W} ${H}" role="img" aria-label="misfit per evaluation">`;
  const every = Math.ceil((hi - lo) / 6);
  for (let k = lo; k <= hi; k += every) {
    const yk = y(10 ** k).toFixed(1);
    s += `<line class="grid" x1="${L}" x2="${W - R}" y1="${yk}" y2="${yk}"/>` +
      `<text x="${L - 4}" y="${yk}" text-anchor="end" dy="0.35em">10<tspan dy="-0.5em" font-size="0.7em">${k}</tspan></text>`;
  }
  if (hi - lo <= 3) // minor lines at 2 and 5 of each decade
    for (let k = lo; k < hi; k++)
      for (const m of [2, 5]) {
        const v = m * 10 ** k, ym = y(v).toFixed(1);
        s += `<line class="minor" x1="${L}" x2="${W - R}" y1="${ym}" y2="${ym}"/>`;
        if (hi - lo <= 2 && v >= 1e-3 && v < 1e5)
          s += `<text class="minor" x="${L - 4}" y="${ym}" text-anchor="end" dy="0.35em">${+v.toPrecision(1)}</text>`;
      }
  for (const t of evaluationTicks(xMax))
    s += `<text x="${x(t).toFixed(1)}" y="${H - B + 14}" text-anchor="middle">${t}</text>`;
  s += `<line class="axis" x1="${L}" x2="${L}" y1="${T}" y2="${H - B}"/><line class="axis" x1="${L}" x2="${W - R}" y1="${H - B}" y2="${H - B}"/>`;
  s += `<text x="${(L + W - R) / 2}" y="${H - 3}" text-anchor="middle">evaluation</text>` +
    `<text x="11" y="${(T + H - B) / 2}" text-anchor="middle" transform="rotate(-90 11 ${(T + H - B) / 2})">χ² (log)</text>`;
  if (evaluations.length) {
    const pts = evaluations.map((e) => `${x(e.n).toFixed(1)},${y(e.chi2).toFixed(1)}`).join(" ");
    const best = bestSoFar(evaluations);
    let step = "";
    evaluations.forEach((e, i) => {
      const bx = x(e.n).toFixed(1), by = y(best[i]).toFixed(1);
      step += i ? ` ${bx},${y(best[i - 1]).toFixed(1)} ${bx},${by}` : `${bx},${by}`;
    });
    s += `<polyline class="path" points="${pts}"/><polyline class="best" points="${step}"/>`;
    evaluations.forEach((e, i) => {
      const colour = STAGE_COLOURS[e.stage] || STAGE_COLOURS.fit;
      const isBest = e.chi2 === best[i] && (i === 0 || best[i] < best[i - 1]);
      s += `<circle data-n="${e.n}" data-chi2="${e.chi2}" cx="${x(e.n).toFixed(1)}" cy="${y(e.chi2).toFixed(1)}" r="${isBest ? 3.2 : 2.4}" ` +
        `fill="${isBest ? colour : "#fff"}" stroke="${colour}"><title>evaluation ${e.n}${e.stage ? " (" + esc(e.stage) + ")" : ""}: ` +
        `χ² = ${typeof e.chi2 === "number" ? +e.chi2.toPrecision(6) : "not finite"}; ` +
        `${esc(Object.entries(e.params || {}).map(([k, v]) => `${k} = ${typeof v === "number" ? +v.toPrecision(5) : v}`).join(", "))}</title></circle>`;
    });
  }
  return s + "</svg>";
}

const STAGE_NAMES = { start: "the starting case", fit: "the fit", "corrected fit": "the corrected fit",
                      uncertainty: "the intervals' Jacobian" };

// The caption under the plot (HTML): the count, the best value, the stages' colours.
export function misfitCaption(evaluations, final) {
  if (!evaluations.length) return final ? "no evaluations" : "waiting for the first evaluation ...";
  const best = bestSoFar(evaluations).pop();
  const stages = final ? [...new Set(evaluations.map((e) => e.stage).filter(Boolean))] : [];
  const legend = stages.map((st) => `<span style="color:${STAGE_COLOURS[st] || STAGE_COLOURS.fit}">●</span> ` +
    esc(STAGE_NAMES[st] || st)).join(", ");
  return `χ² of each evaluation, log scale (filled: a new best; line: the best so far): ${evaluations.length} ` +
    `evaluations, best ${+best.toPrecision(4)}` + (final ? (legend ? `; ${legend}` : "") : " (live)");
}

// The stage line of a running calibration from its evaluations.
export function evaluationStage(evaluations, maxEvals) {
  if (!evaluations.length) return null;
  const e = evaluations[evaluations.length - 1], best = bestSoFar(evaluations).pop();
  const chi2 = typeof e.chi2 === "number" ? +e.chi2.toPrecision(4) : "not finite";
  return `evaluation ${e.n} (fit: at most ${maxEvals}): χ² = ${chi2}, best ${+best.toPrecision(4)}`;
}
