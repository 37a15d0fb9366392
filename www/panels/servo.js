// Servo & Best K_FFP panel (suzuki-best-kffp). JS gathers inputs, calls the
// core in the worker, draws and offers downloads; every number is computed
// in Rust (feedVectorTest, bestKffp, torqueSaturation, frequencyResponse,
// analyzeFeedVectorTrace, bestKffpFromTrace).
import { h, table, fmt, numberField, selectField, downloadText, toCsv, dropZone, progressBar, runState, showError } from '../lib/ui.js';
import { lineChart } from '../lib/plot.js';
import { mapCalls } from '../lib/pool.js';

const FIELDS = [
  ['j', 'J', 'kg·m²'], ['c', 'C', 'N·m·s/rad'], ['kpp', 'Kpp', '1/s'], ['kvp', 'Kvp', 'N·m·s/rad'], ['kvi', 'Kvi', 'N·m/rad'],
  ['kffp', 'K_FFP', '%'], ['ts', 'Ts', 's'], ['ta', 'Ta', 's'], ['tp', 'Tp', 's'], ['torqueMax', 'torque max', 'N·m'], ['lead', 'lead', 'm'],
];

/**
 * A core error about the axis table in the page's terms: the parameter by
 * its row label, axis column and unit ("C axis, Kpp [1/s]: empty; …"), not
 * by its API path ("machine.axes.c: missing key 'kpp'"). Other messages
 * pass unchanged.
 * @param {unknown} e
 */
export function inTableTerms(e) {
  const message = e instanceof Error ? e.message : String(e);
  const label = (a, f) => {
    const row = FIELDS.find(([k]) => k === f);
    return row ? `${a.toUpperCase()} axis, ${row[1]} [${row[2]}]` : null;
  };
  const said = message
    .replace(/machine\.axes\.(\w+): missing key '(\w+)'/g, (m, a, f) => (label(a, f) ? `${label(a, f)}: empty; enter a value in the axis table` : m))
    .replace(/machine\.axes\.(\w+)\.(\w+):/g, (m, a, f) => (label(a, f) ? `${label(a, f)}:` : m))
    .replace(/axis (\w+): axis parameter `(\w+)`/g, (m, a, f) => label(a, f) ?? m);
  return new Error(said);
}

/**
 * @param {HTMLElement} root
 * @param {import('../lib/api.js').Api} api
 */
export async function mount(root, api) {
  const machine = await api.call('machinePreset', ['nmv5000']);
  const axes = Object.keys(machine.axes);
  // The paper's conditions and quoted values are the preset's data (Rust:
  // machine::paper_sweep), not the page's.
  const paper = machine.paperSweep;
  if (!paper) throw new Error(`machine preset '${machine.name}' has no paperSweep: the servo panel needs the paper's test conditions`);

  // ---- parameter table (editable) ----
  const inputs = {};
  /** A parameter as the table shows it (empty when the preset has none). */
  const shown = (v) => (v === undefined ? '' : String(v));
  const cell = (a, f) => {
    const input = h('input', { type: 'number', step: 'any', id: `servo-p-${a}-${f}`, value: shown(machine.axes[a][f]), style: 'width:6.5em' });
    inputs[`${a}.${f}`] = input;
    return input;
  };
  const paramTable = table(['parameter', 'unit', ...axes.map((a) => a.toUpperCase())], FIELDS.map(([f, label, unit]) => [label, unit, ...axes.map((a) => cell(a, f))]));
  paramTable.querySelector('table').id = 'servo-preset-table';
  // The paper's loop readings (machinePreset(name, reading)): choosing one
  // refills the table with that reading's values.
  const readings = machine.loopReadings ?? [];
  const READING_TEXT = { table: 'Table 1 as printed', kppText: 'K_pp = 30 1/s as the text says', inertiaAtLoad: 'X inertia on the load side of the screw' };
  const readingSel = selectField({
    label: 'Loop reading', id: 'servo-loop-reading', value: readings[0], options: readings.map((r) => [r, `${r} — ${READING_TEXT[r] ?? r}`]),
    onChange: async (r) => {
      try {
        const m = await api.call('machinePreset', [machine.name, r]);
        for (const a of axes) {
          for (const [f] of FIELDS) inputs[`${a}.${f}`].value = shown(m.axes[a][f]);
        }
        inputs['c.j'].dispatchEvent(new Event('input'));
      } catch (e) {
        showError(out, e);
      }
    },
  });
  const currentMachine = () => {
    const m = structuredClone(machine);
    for (const a of axes) {
      for (const [f] of FIELDS) {
        const s = inputs[`${a}.${f}`].value;
        if (s === '') delete m.axes[a][f];
        else m.axes[a][f] = Number(s);
      }
    }
    return m;
  };

  // ---- condition ----
  // The J+J1 labels follow the C axis' J as edited in the table.
  const j1Label = (v) => `${v} kg·m² (J+J1 = ${fmt(Number(inputs['c.j'].value) + v, 2)})`;
  const j1 = selectField({ label: 'J1 (load on C)', id: 'servo-j1', value: String(paper.j1[0]), options: paper.j1.map((v) => [String(v), j1Label(v)]) });
  inputs['c.j'].addEventListener('input', () => {
    for (const [i, o] of [...j1.input.options].entries()) o.textContent = j1Label(paper.j1[i]);
  });
  const mode = selectField({ label: 'speed given as', id: 'servo-mode', value: 'omega', options: [['omega', 'ω [rad/s]'], ['feed', 'F_C [mm/min] with R_C']] });
  const omega = numberField({ label: 'ω', unit: 'rad/s', value: Math.PI.toFixed(6), id: 'servo-omega' });
  const feed = numberField({ label: 'F_C', unit: 'mm/min', value: paper.feedAtCuttingPoint, id: 'servo-feed' });
  const rc = numberField({ label: 'R_C', unit: 'mm', value: paper.rc, id: 'servo-rc' });
  const rw = numberField({ label: 'R_W', unit: 'mm', value: paper.rw, id: 'servo-rw' });
  const freqUnit = selectField({ label: 'Bode frequency axis', id: 'servo-bode-unit', value: 'rad', options: [['rad', 'ω [rad/s]'], ['hz', 'f [Hz]']], onChange: () => last?.before && draw() });
  const accel = numberField({ label: 'accel time', unit: 's', value: paper.accelTime, id: 'servo-accel' });
  const dt = numberField({ label: 'time step', unit: 's', value: 0.001, id: 'servo-dt' });
  const condition = (over = {}) => {
    const w = mode.value === 'omega' ? omega.value : feed.value / 60 / rc.value;
    return { rc: rc.value, rw: rw.value, omega: w, accelTime: accel.value, j1: Number(j1.value), dt: dt.value, ...over };
  };

  // ---- outputs ----
  const status = h('div', { id: 'servo-status', class: 'lead' });
  const out = h('div', { id: 'servo-results' });
  const progress = progressBar();
  const charts = h('div', { id: 'servo-charts' });
  const runUi = runState(out, charts);
  const setDownloads = (on) => {
    for (const id of ['servo-csv', 'servo-json']) {
      const b = /** @type {HTMLButtonElement | null} */ (root.querySelector(`#${id}`));
      if (b) b.disabled = !on;
    }
  };
  const sweepBox = h('div', { id: 'servo-sweep-results' });
  const traceBox = h('div', { id: 'servo-trace-results' });
  const sweepUi = runState(sweepBox);
  const traceUi = runState(traceBox);
  // ---- Best K_FFP from the measured trace (suzuki §4.7, anchored on it) ----
  // The set the trace was measured with and its load are required: the
  // recommendation depends on them, so nothing is assumed.
  const measuredK = ['x', 'y', 'c'].map((a) => numberField({ label: `K_FFP ${a.toUpperCase()} during the trace`, unit: '%', value: '', id: `servo-tk-${a}` }));
  const traceJ1 = numberField({ label: 'J1 during the trace', unit: 'kg·m²', value: '', id: 'servo-tk-j1', min: 0 });
  const identify = h('input', { type: 'checkbox', id: 'servo-tk-identify' });
  const recBox = h('div', { id: 'servo-tk-results' });
  const recUi = runState(recBox);
  const recommend = async () => {
    recUi.start();
    try {
      if (!last?.traceText) throw new Error('analyse a measured trace first (drop it above and press "Analyse the trace")');
      const [kx, ky, kc] = measuredK.map((f) => f.value);
      for (const f of measuredK) if (!Number.isFinite(f.value)) throw new Error(`${f.el.querySelector('span').textContent}: enter the K_FFP the control had when the trace was recorded`);
      if (!Number.isFinite(traceJ1.value)) throw new Error('J1 during the trace [kg·m²]: enter the load on C when the trace was recorded');
      const m = currentMachine();
      const cond = condition({ j1: traceJ1.value, kffp: { x: kx, y: ky, c: kc } });
      const r = await api.call('bestKffpFromTrace', [m, cond, last.traceText, last.mapping, { identify: identify.checked }]);
      const mrad = (v) => fmt(v * 1e3, 4);
      const um = (v) => fmt(v * 1e3, 2);
      const t = table(['', 'K_FFP X / Y / C [%]', 'mean α − β [mrad]', 'shape error half ampl. [µm]'], [
        ['measured (your trace)', `${fmt(r.measuredWith.x, 2)} / ${fmt(r.measuredWith.y, 2)} / ${fmt(r.measuredWith.c, 2)}`, mrad(r.measured.meanAngleDiff), um(r.measured.halfAmplitude)],
        ['your axis model, same set', '', mrad(r.modelBefore.meanAngleDiff), um(r.modelBefore.halfAmplitude)],
        [h('b', {}, 'recommended'), h('b', { id: 'servo-tk-kffp' }, `${fmt(r.kffp.x, 2)} / ${fmt(r.kffp.y, 2)} / ${fmt(r.kffp.c, 2)}`), h('span', { id: 'servo-tk-after' }, mrad(r.predictedMeanAngleDiff)), um(r.predictedHalfAmplitude)],
      ]);
      t.querySelector('table').id = 'servo-tk-table';
      const ident = r.identified.length
        ? table(['axis', 'Kpp [1/s]', 'Kvp [N·m·s/rad]', 'C [N·m·s/rad]', 'RMS residual [µm]'], r.identified.map((a) => [a.axis.toUpperCase(), fmt(a.params.kpp, 3), fmt(a.params.kvp, 4), fmt(a.params.c, 4), fmt(a.rmsPosition * 1e3, 3)]))
        : '';
      recBox.replaceChildren(
        h('p', {}, `On your axis (the table above${r.identified.length ? ', with X and Y identified from the trace' : ''}) at J1 = ${fmt(traceJ1.value, 3)} kg·m², ${r.method}: the model's mismatch at the measured set is ${mrad(r.mismatch)} mrad, taken into the recommendation.`),
        t, ident,
        h('button', { id: 'servo-tk-json', onclick: () => downloadText('kffp-from-trace.json', JSON.stringify({ machine: m, condition: cond, mapping: last.mapping, result: r }, null, 2), 'application/json') }, 'Download (JSON)'),
      );
      recUi.ok();
    } catch (e) {
      recUi.fail(inTableTerms(e));
    }
  };
  const recCard = h('div', { class: 'subcard', id: 'servo-tk' },
    h('h4', {}, 'Best K_FFP from this trace'),
    h('p', { class: 'unit' }, 'Recommends the K_FFP that makes α − β zero on your axis, anchored on the measured α − β (suzuki §4.7). Enter the set and the load the trace was recorded with.'),
    h('div', { class: 'row' }, ...measuredK.map((f) => f.el), traceJ1.el, h('label', { class: 'field' }, h('span', {}, 'identify X and Y from the trace'), identify)),
    h('button', { id: 'servo-tk-run', onclick: recommend }, 'Recommend K_FFP from this trace'), recBox);
  let last = null; // { cond, before, best, after, trace }

  const summaryRows = (label, s) => [label, fmt(s.meanAngleDiff * 1e3, 4), fmt(s.halfAmplitude * 1e3, 2), fmt(s.radiusDecrease * 1e3, 2), fmt(s.peakTorque, 0), s.saturated ? 'yes' : 'no'];
  const summaryTable = (rows) => table(['', 'mean α−β [mrad]', 'half amplitude [µm]', 'radius decrease [µm]', 'peak C torque [N·m]', 'saturated'], rows);

  const draw = async () => {
    const { cond, before, after, m } = last;
    const t = before.series.t;
    const series = [{ label: `K_FFP set` }];
    const shape = [t, before.series.shapeError.map((v) => v * 1e3)];
    const diff = [t, before.series.angleDiff.map((v) => v * 1e3)];
    if (after) {
      series.push({ label: 'Best K_FFP', dash: [6, 3] });
      shape.push(after.series.shapeError.map((v) => v * 1e3));
      diff.push(after.series.angleDiff.map((v) => v * 1e3));
    }
    if (last.trace && last.trace.series.t.length) {
      const tr = last.trace.series;
      // the measured trace on the simulation's time base (nearest sample; display only)
      const idx = (x) => Math.min(tr.t.length - 1, Math.max(0, Math.round((x - tr.t[0]) / ((tr.t[tr.t.length - 1] - tr.t[0]) / (tr.t.length - 1)))));
      series.push({ label: 'measured trace', color: '#495057' });
      shape.push(Array.from(t, (x) => (x >= tr.t[0] && x <= tr.t[tr.t.length - 1] ? tr.shapeError[idx(x)] * 1e3 : null)));
      diff.push(Array.from(t, (x) => (x >= tr.t[0] && x <= tr.t[tr.t.length - 1] ? tr.angleDiff[idx(x)] * 1e3 : null)));
    }
    const band = [{ from: before.summary.steadyFrom, to: t[t.length - 1], label: 'steady state' }];
    const limit = m.axes.c.torqueMax;
    const els = Array.from({ length: 5 }, () => h('div'));
    charts.replaceChildren(...els);
    lineChart(els[0], { title: 'Shape error ΔR_C (Figs. 12, 25)', xLabel: 't [s]', yLabel: 'µm', series, data: shape, bands: band });
    lineChart(els[1], { title: 'Relative angle difference α − β (Figs. 13, 23)', xLabel: 't [s]', yLabel: 'mrad', series, data: diff, bands: band });
    const s = (after || before).series;
    lineChart(els[2], { title: `Angular velocity of each axis${after ? ' (Best K_FFP)' : ''} (Figs. 16, 24)`, xLabel: 't [s]', yLabel: 'rad/s', series: [{ label: 'C' }, { label: 'X–Y about the centre' }], data: [t, s.omegaC, s.omegaL] });
    els[3].id = 'servo-torque-chart';
    lineChart(els[3], { title: 'C torque against its limit (Figs. 17, 19)', xLabel: 't [s]', yLabel: 'N·m', series: [{ label: 'C torque' }], data: [t, before.series.torqueC], hLines: limit ? [{ y: limit, label: `+${limit} N·m` }, { y: -limit, label: `−${limit} N·m` }] : [] });
    const ws = Float64Array.from({ length: 200 }, (_, i) => 0.1 * 10 ** (i / 50));
    const bode = await Promise.all(axes.map((a) => api.call('frequencyResponse', [{ ...m.axes[a], j1: a === 'c' ? cond.j1 : m.axes[a].j1, kffp: after ? last.best.kffp[a] : m.axes[a].kffp }, ws])));
    const bodeEl = [h('div'), h('div')];
    els[4].replaceChildren(...bodeEl);
    // Frequency axis in rad/s or Hz (f = ω/2π); curves dashed by axis so
    // that equal responses (X and Y share their tuning) stay visible.
    const hz = freqUnit.value === 'hz';
    const fs = hz ? ws.map((w) => w / (2 * Math.PI)) : ws;
    const fLabel = hz ? 'f [Hz]' : 'ω [rad/s]';
    const bodeSeries = axes.map((a, i) => ({ label: a.toUpperCase(), dash: [[], [8, 4], [2, 3]][i % 3], width: 2 - (i % 3) * 0.3 }));
    lineChart(bodeEl[0], { title: `Bode magnitude per axis${after ? ' (Best K_FFP)' : ''}`, xLabel: fLabel, yLabel: 'dB', scales: { x: { time: false, distr: 3 } }, series: bodeSeries, data: [fs, ...bode.map((b) => b.magnitude.map((v) => 20 * Math.log10(v)))] });
    lineChart(bodeEl[1], { title: 'Bode phase per axis', xLabel: fLabel, yLabel: 'deg', scales: { x: { time: false, distr: 3 } }, series: bodeSeries, data: [fs, ...bode.map((b) => b.phase.map((v) => (v * 180) / Math.PI))] });
  };

  const showResults = () => {
    const { cond, before, best, after } = last;
    const rows = [summaryRows('simulated, K_FFP set', before.summary)];
    if (after) rows.push(summaryRows(`simulated, Best K_FFP (${best.method})`, after.summary));
    if (last.trace) rows.push(summaryRows('measured trace', last.trace.summary));
    const kffpTable = best
      ? table(['axis', 'set K_FFP [%]', 'Best K_FFP [%]'], axes.map((a) => [a.toUpperCase(), fmt(last.m.axes[a].kffp, 2), h('span', { id: `servo-kffp-${a}` }, fmt(best.kffp[a], 3))]))
      : '';
    if (kffpTable) kffpTable.querySelector('table').id = 'servo-kffp-table';
    out.replaceChildren(
      h('p', {}, `ω = ${fmt(cond.omega, 4)} rad/s, J + J1 = ${fmt(last.m.axes.c.j + cond.j1, 2)} kg·m². Mean α − β: `, h('b', { id: 'servo-mean-angle-diff' }, fmt(before.summary.meanAngleDiff * 1e3, 4)), ' mrad; half amplitude of the shape error: ', h('b', { id: 'servo-half-amplitude' }, fmt(before.summary.halfAmplitude * 1e3, 2)), ' µm.'),
      best ? h('p', {}, 'α_th of C (Eq. 17): ', h('b', { id: 'servo-alpha-th' }, fmt(best.alphaTh * 1e3, 4)), ' mrad; after Best K_FFP the simulated mean α − β is ', h('b', { id: 'servo-after-angle-diff' }, fmt(after.summary.meanAngleDiff * 1e3, 4)), ' mrad.') : '',
      summaryTable(rows),
      kffpTable,
    );
  };

  const run = async (withBest) => {
    status.textContent = 'running in the worker…';
    runUi.start();
    setDownloads(false);
    if (last) last.before = null;
    try {
      const m = currentMachine();
      const cond = condition();
      const before = await api.call('feedVectorTest', [m, cond]);
      let best = null;
      let after = null;
      if (withBest) {
        best = await api.call('bestKffp', [m, cond]);
        after = await api.call('feedVectorTest', [m, { ...cond, kffp: best.kffp }]);
      }
      last = { m, cond, before, best, after, trace: last?.trace && last.traceText ? await api.call('analyzeFeedVectorTrace', [last.traceText, cond, last.mapping]) : null, traceText: last?.traceText, mapping: last?.mapping };
      showResults();
      await draw();
      runUi.ok();
      setDownloads(true);
      status.textContent = 'done';
    } catch (e) {
      status.textContent = '';
      runUi.fail(inTableTerms(e));
    }
  };

  // ---- the sweep (Figs. 14, 15, 20, 22) and the saturation map (Fig. 21) ----
  // On the user's axis (the table) and the user's loads and speeds; the
  // paper's lists are the defaults. The paper's quoted numbers are shown
  // beside ours only for the paper's own case (preset table, paper's loads).
  const sweepJ1 = h('input', { id: 'servo-sweep-j1', value: paper.j1.join(', '), size: 18, title: 'Load inertias J1 on C, comma-separated' });
  const sweepOmega = h('input', { id: 'servo-sweep-omega', value: paper.omega.map((w) => +w.toFixed(6)).join(', '), size: 30, title: 'Angular velocities ω, comma-separated' });
  /** The numbers of a comma-separated list field, or an error naming the field. */
  const listOf = (input, label) => {
    const parts = input.value.split(/[,;\s]+/).filter(Boolean);
    if (!parts.length) throw new Error(`${label}: enter one value or more, comma-separated`);
    return parts.map((p) => {
      const v = Number(p);
      if (!Number.isFinite(v)) throw new Error(`${label}: '${p.slice(0, 20)}' is not a number`);
      return v;
    });
  };
  const sameList = (a, b) => a.length === b.length && a.every((v, i) => Math.abs(v - b[i]) <= 1e-6 * Math.max(1, Math.abs(b[i])));
  /** True when the axis table holds the preset's values (the paper's axis). */
  const presetTable = () => axes.every((a) => FIELDS.every(([f]) => inputs[`${a}.${f}`].value === shown(machine.axes[a][f])));
  const sweep = async () => {
    const m = currentMachine();
    const rows = [];
    let done = 0;
    sweepUi.start();
    try {
      const loads = listOf(sweepJ1, 'Sweep loads J1 [kg·m²]');
      const omegas = listOf(sweepOmega, 'Sweep ω [rad/s]');
      const papers = presetTable() && sameList(loads, paper.j1) && sameList(omegas, paper.omega);
      const data = loads.map(() => ({ before: [], after: [], half: [], kx: [], ky: [] }));
      // J + J1 per load as the core sums it (the C axis' J as edited); the
      // torque limit is the machine's C torqueMax (the core names it if absent).
      const { rc: rcP, rw: rwP, accelTime, feedAtCuttingPoint } = paper;
      const sat = await api.call('torqueSaturation', [m, { j1: loads, accelTime, feedAtCuttingPoint, dt: dt.value }]);
      // One bestKffp per (J1, ω) on all cores (lib/pool.js), in order.
      const args = loads.flatMap((jv) => omegas.map((w) => [m, { rc: rcP, rw: rwP, omega: w, accelTime, j1: jv, dt: dt.value }]));
      const results = await mapCalls(api, 'bestKffp', args, { onProgress: (d, n) => progress.set(d / n, `${d} of ${n} points`) });
      for (const ji of loads.keys()) {
        for (const w of omegas) {
          const r = results[done];
          data[ji].before.push(r.before.meanAngleDiff * 1e3);
          data[ji].after.push(r.after.meanAngleDiff * 1e3);
          data[ji].half.push(r.before.halfAmplitude * 1e3);
          rows.push([fmt(sat[ji].jTotal, 2), `${fmt(w / Math.PI, 1)}π`, fmt(r.before.meanAngleDiff * 1e3, 3), fmt(r.before.halfAmplitude * 1e3, 1), r.before.saturated ? 'yes' : 'no', r.method, fmt(r.kffp.x, 2), fmt(r.kffp.y, 2), fmt(r.after.meanAngleDiff * 1e3, 4), fmt(r.after.halfAmplitude * 1e3, 1)]);
          done++;
        }
      }
      progress.done();
      const els = [h('div'), h('div'), h('div')];
      const t = table(['J+J1 [kg·m²]', 'ω', 'α−β [mrad]', 'half ampl. [µm]', 'saturated', 'method', 'Best K_FFP X [%]', 'Best K_FFP Y [%]', 'α−β after [mrad]', 'half ampl. after [µm]'], rows);
      t.querySelector('table').id = 'servo-sweep-table';
      // paper / ours / why: the points suzuki §5.2 quotes, from the preset (paperSweep.saturation).
      // as the paper prints them
      const quoted = (i, key) => String(paper.saturation[i]?.[key] ?? '—');
      const satTable = papers
        ? table(['J+J1 [kg·m²]', 'accelSat paper / ours [rad/s²]', 'ωsat paper / ours [rad/s]', `R_C min paper / ours at ${feedAtCuttingPoint} mm/min [mm]`], sat.map((p, i) => [fmt(p.jTotal, 2), `${quoted(i, 'accelSat')} / ${fmt(p.accelSat, 1)}`, `${quoted(i, 'omegaSat')} / ${fmt(p.omegaSat, 3)}`, `${quoted(i, 'rcMin')} / ${fmt(p.rcMin, 3)}`]))
        : table(['J+J1 [kg·m²]', 'accelSat, your axis [rad/s²]', 'ωsat, your axis [rad/s]', `R_C min at ${feedAtCuttingPoint} mm/min, your axis [mm]`], sat.map((p) => [fmt(p.jTotal, 2), fmt(p.accelSat, 1), fmt(p.omegaSat, 3), fmt(p.rcMin, 3)]));
      satTable.append(h('p', { class: 'note', id: 'servo-sweep-whose' }, papers
        ? `The paper's own case (preset axis table, its loads and speeds), so its quoted points are shown beside ours. Why they differ: reading 'preControlOff' (commanded acceleration ω/${accelTime} s, C loop with K_FFP = 0; the paper does not state Fig. 17's K_FFP). The paper's three points scatter ±4.7 % in ω·J, so no reading matches all three within 2 %; see docs/readings.md.`
        : `Your axis (the table above${presetTable() ? '' : ', as edited'}) and your loads: the paper's quoted points belong to its own axis and loads and are not shown. Reading 'preControlOff': commanded acceleration ω/${accelTime} s, C loop with K_FFP = 0.`));
      satTable.querySelector('table').id = 'servo-saturation-table';
      sweepBox.replaceChildren(...els, t, h('h4', {}, 'Torque-saturation limits (Figs. 17, 21)'), satTable);
      sweepUi.ok();
      const series = sat.map((p) => ({ label: `J+J1 = ${fmt(p.jTotal, 2)}` }));
      // uPlot needs ascending x: the points in ω order
      const order = [...omegas.keys()].sort((a, b) => omegas[a] - omegas[b]);
      const byOmega = (v) => order.map((i) => v[i]);
      lineChart(els[0], { title: 'Mean α − β with K_FFP set (Figs. 15, 20)', xLabel: 'ω [rad/s]', yLabel: 'mrad', series, data: [byOmega(omegas), ...data.map((d) => byOmega(d.before))] });
      lineChart(els[1], { title: 'Half amplitude of the shape error (Fig. 14)', xLabel: 'ω [rad/s]', yLabel: 'µm', series, data: [byOmega(omegas), ...data.map((d) => byOmega(d.half))] });
      const rcs = Float64Array.from({ length: 200 }, (_, i) => 0.1 + (i * 5.9) / 199);
      lineChart(els[2], {
        title: `R_C – ω_R map with the saturation ω per load; R_C min at ${feedAtCuttingPoint} mm/min (Figs. 5, 21)`, xLabel: 'R_C [mm]', yLabel: 'ω_R [rad/s]',
        series: [100, 200, 400].map((f) => ({ label: `F_C = ${f} mm/min` })),
        data: [rcs, ...[100, 200, 400].map((f) => rcs.map((r) => f / 60 / r))],
        scales: { x: { time: false }, y: { range: [0, 20] } },
        // Greys, apart from the F_C curves' palette colours; short labels that fit the plot.
        hLines: sat.map((p, i) => ({ y: p.omegaSat, label: `ω_sat, J+J1 = ${fmt(p.jTotal, 2)} (R_C min ${fmt(p.rcMin, 2)} mm)`, color: ['#212529', '#495057', '#868e96'][i % 3] })),
      });
    } catch (e) {
      progress.done();
      sweepUi.fail(inTableTerms(e));
    }
  };

  // ---- trace import ----
  const mapBox = h('div', { id: 'servo-trace-mapper' });
  const traceInfo = h('p', { id: 'servo-trace-file', class: 'unit' }, 'No trace loaded. Expected columns: time, X, Y, C (and optionally torque), units in the header such as Time [ms] or X_mm.');
  const traceRefused = (e, name) => {
    mapBox.replaceChildren();
    if (last) last.trace = null;
    traceInfo.textContent = `${name}: not loaded (see the error below).`;
    traceUi.fail(e);
  };
  // A file of numbers only (halsampler) has no time axis: the core asks
  // for its sample period, and the file is read again when it is given.
  let dropped = null;
  const period = numberField({ label: 'sample period', unit: 's; only for a file of numbers without a time column (halsampler)', value: '', id: 'servo-trace-period', min: 0, onChange: () => dropped && onTrace(dropped.text, dropped.name) });
  const readOptions = () => (period.input.value === '' ? undefined : { samplePeriod: period.value });
  /** @param {string | Uint8Array} text @param {string} name */
  const onTrace = async (text, name) => {
    // The core reads the file (its layout: delimited text, a TwinCAT Scope
    // export, halsampler/halscope, a SINUMERIK trace, a .mat capture; the
    // delimiter, decimal commas, metadata, text columns, the unit each
    // header states and its factor, and which column it reads as which):
    // the page shows that layout and fills its menus from it.
    dropped = { text, name };
    mapBox.replaceChildren();
    traceUi.clear();
    if (last) last.trace = null;
    let layout;
    try {
      layout = await api.call('traceLayout', [text, readOptions(), 'feedVector']);
    } catch (e) {
      traceRefused(e, name);
      return;
    }
    const columns = layout.columns.filter((c) => c.kind !== 'text');
    traceInfo.textContent = `${name} (layout read: ${layout.format}): ${layout.rows} rows, columns ${columns.map((c) => c.name).join(', ')}`;
    const preview = table(['field', 'column', 'read as', 'unit', 'to core units', 'note'], layout.columns.map((c) => [c.field || '—', c.name, c.role ? `${c.kind}: ${c.role}` : c.kind, c.unit ?? '—', c.factor != null ? `× ${+c.factor.toPrecision(6)} → ${c.coreUnit}` : '—', c.note ?? '']));
    preview.querySelector('table').id = 'servo-trace-layout';
    const said = h('ul', { id: 'servo-trace-notes', class: 'note' }, ...layout.notes.map((n) => h('li', {}, n)), ...layout.metadata.map((m) => h('li', {}, `line ${m.line}: ${m.key}${m.value ? ` = ${m.value}` : ''}`)));
    // Each menu starts at the column the core reads for that role (the
    // layout's `role`): the page guesses nothing.
    const pick = (id, label, role) => selectField({ label, id, value: columns.find((c) => c.role === role)?.name || '', options: [['', '—'], ...columns.map((c) => [c.name, c.name])] });
    const cols = { time: pick('servo-map-time', 'time', 'time'), x: pick('servo-map-x', 'X', 'x'), y: pick('servo-map-y', 'Y', 'y'), c: pick('servo-map-c', 'C', 'c'), torque: pick('servo-map-torque', 'torque', 'torque') };
    const info = (sel) => columns.find((c) => c.name === sel.value);
    // Each unit menu lists the core's units of its quantity; its value is
    // the core's factor to core units for the column chosen.
    const LABEL = { us: 'µs', um: 'µm', n·m: 'N·m' };
    const unitMenu = (id, label, quantity, fallback) => {
      const units = layout.units.filter((u) => u.quantity === quantity);
      const dflt = String(units.find((u) => u.code === fallback).factor);
      const menu = selectField({ label, id, value: dflt, options: units.map((u) => [String(u.factor), LABEL[u.code] ?? u.code]) });
      const follow = (sel) => {
        const c = info(sel);
        menu.value = c?.quantity === quantity ? String(c.factor) : dflt;
      };
      return { menu, follow };
    };
    const tUnit = unitMenu('servo-map-tunit', 'time unit', 'time', 's');
    const lUnit = unitMenu('servo-map-lunit', 'X, Y unit', 'length', 'mm');
    const aUnit = unitMenu('servo-map-aunit', 'C unit', 'angle', 'deg');
    const follows = [[cols.time, tUnit], [cols.x, lUnit], [cols.c, aUnit]];
    for (const [sel, u] of follows) {
      u.follow(sel);
      // Choosing another column takes its stated unit.
      sel.input.addEventListener('change', () => u.follow(sel));
    }
    const rated = numberField({ label: 'rated torque', unit: 'N·m; needed for a torque in %', value: '', id: 'servo-map-rated', min: 0 });
    const rel = h('input', { type: 'checkbox', id: 'servo-map-relative' });
    // Blank: the first sample, and accel time + 0.4 s after it (the core's defaults).
    const start = numberField({ label: 'motion start', unit: 's, trace time; blank: first sample', value: '', id: 'servo-map-start' });
    const steady = numberField({ label: 'steady window from', unit: 's after the start; blank: accel time + 0.4 s', value: '', id: 'servo-map-steady', min: 0 });
    const go = h('button', { id: 'servo-trace-run', onclick: async () => {
      // The menus hold the core's factors: they scale every column.
      const mapping = { headerUnits: false, timeScale: Number(tUnit.menu.value), linearScale: Number(lUnit.menu.value), angleScale: Number(aUnit.menu.value), relative: rel.checked };
      if (period.input.value !== '') mapping.samplePeriod = period.value;
      if (rated.input.value !== '') mapping.ratedTorque = rated.value;
      for (const [k, s] of Object.entries(cols)) if (s.value) mapping[k] = s.value;
      if (start.input.value !== '') mapping.motionStart = start.value;
      if (steady.input.value !== '') mapping.steadyFrom = steady.value;
      traceUi.start();
      try {
        const trace = await api.call('analyzeFeedVectorTrace', [text, condition(), mapping]);
        last = { ...(last || {}), trace, traceText: text, mapping };
        traceBox.replaceChildren(
          h('p', {}, `${name}: ${trace.series.t.length} samples; mean α − β `, h('b', { id: 'servo-trace-angle-diff' }, fmt(trace.summary.meanAngleDiff * 1e3, 4)), ' mrad.'),
          summaryTable([summaryRows('measured trace', trace.summary)]),
        );
        traceUi.ok();
        if (last.before) {
          showResults();
          await draw();
        }
      } catch (e) {
        if (last) last.trace = null;
        traceUi.fail(inTableTerms(e));
      }
    } }, 'Analyse the trace');
    mapBox.replaceChildren(preview, said, h('div', { class: 'row' }, ...Object.values(cols).map((c) => c.el), tUnit.menu.el, lUnit.menu.el, aUnit.menu.el, rated.el, h('label', { class: 'field' }, h('span', {}, 'displacements from the start'), rel), start.el, steady.el), go);
  };

  // ---- downloads ----
  const csv = () => {
    if (!last?.before) return;
    const s = last.before.series;
    const cols = { t_s: s.t, x_cmd_mm: s.xCmd, y_cmd_mm: s.yCmd, c_cmd_rad: s.cCmd, x_mm: s.x, y_mm: s.y, c_rad: s.c, torque_c_Nm: s.torqueC, shape_error_mm: s.shapeError, alpha_rad: s.alpha, beta_rad: s.beta, angle_diff_rad: s.angleDiff, radius_error_mm: s.radiusError };
    if (last.after) Object.assign(cols, { best_x_mm: last.after.series.x, best_y_mm: last.after.series.y, best_shape_error_mm: last.after.series.shapeError, best_angle_diff_rad: last.after.series.angleDiff });
    downloadText('feed-vector-test.csv', toCsv(cols), 'text/csv');
  };
  const json = () => {
    if (!last?.before) return;
    downloadText('feed-vector-test.json', JSON.stringify({ machine: last.m, condition: last.cond, before: last.before.summary, bestKffp: last.best, after: last.after?.summary, trace: last.trace?.summary }, null, 2), 'application/json');
  };

  // Results shown are marked outdated as soon as an input they came from is
  // edited: the axis table feeds every result, the condition every run.
  const conditionFields = [j1.el, mode.el, omega.el, feed.el, rc.el, rw.el, accel.el, dt.el];
  runUi.dependsOn(paramTable, readingSel.el, ...conditionFields);
  sweepUi.dependsOn(paramTable, readingSel.el, sweepJ1, sweepOmega);
  traceUi.dependsOn(paramTable, readingSel.el, mapBox, ...conditionFields);
  recUi.dependsOn(paramTable, readingSel.el, mapBox, recCard, ...conditionFields);
  const sweepCard = h('div', { class: 'card' }, h('h3', {}, `Sweep and saturation map on your axis (the table above), at R_C = ${paper.rc} mm, R_W = ${paper.rw} mm (Figs. 14, 15, 20, 21, 22)`),
    h('p', { class: 'unit' }, `Defaults: the paper's loads and speeds (ω = ${paper.omega.map((w) => `${+(w / Math.PI).toFixed(3)}π`).join(', ')} rad/s); source: ${paper.source}.`),
    h('div', { class: 'row' }, h('label', { class: 'field' }, h('span', {}, 'Loads J1 ', h('span', { class: 'unit' }, '[kg·m²]')), sweepJ1), h('label', { class: 'field' }, h('span', {}, 'ω ', h('span', { class: 'unit' }, '[rad/s]')), sweepOmega)),
    h('button', { id: 'servo-sweep', onclick: sweep }, 'Run the sweep'), progress.el, sweepBox);
  root.replaceChildren(
    h('div', { class: 'card' }, h('h3', {}, `Preset ${machine.name}`), h('p', {}, machine.description), h('p', { class: 'lead' }, `Source: ${machine.source}. Edit any value; the C torque limit is ${machine.axes.c.torqueMax} N·m.`), ...(readings.length > 1 ? [readingSel.el, h('p', { class: 'note' }, 'The paper leaves open how to read Table 1 for the X loop; only the load-side X inertia gives its ΔR > 0 on X (docs/readings.md).')] : []), paramTable),
    h('div', { class: 'card' }, h('h3', {}, 'Constant-feed-speed-vector test (§2.3, §3)'), h('div', { class: 'row' }, j1.el, mode.el, omega.el, feed.el, rc.el, rw.el, accel.el, dt.el, freqUnit.el),
      h('div', { class: 'row' },
        h('button', { id: 'servo-run', dataset: { run: '' }, onclick: () => run(false) }, 'Simulate'),
        h('button', { id: 'servo-best', onclick: () => run(true) }, 'Best K_FFP'),
        h('button', { id: 'servo-csv', onclick: csv }, 'Download CSV'),
        h('button', { id: 'servo-json', onclick: json }, 'Download JSON')),
      status, out, charts),
    h('div', { class: 'card' }, h('h3', {}, 'Measured trace (SERVO GUIDE-style CSV/TSV: time, X, Y, C, torque)'), period.el, dropZone({ link: 'servo-trace', label: 'Drop a trace here (CSV/TSV, TwinCAT Scope export, halsampler/halscope, SINUMERIK trace XML, MATLAB .mat), or click to choose one', accept: '.csv,.tsv,.txt,.dat,.xml,.mat', onText: onTrace, onBytes: onTrace, onRefused: traceRefused }), traceInfo, mapBox, traceBox, recCard),
    sweepCard,
  );
}
