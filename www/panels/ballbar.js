// Ball bar & alignment panel: load a ball-bar trace (or generate a synthetic
// one), fit its centre, its harmonics, the ISO 230-4 table and diagnostics,
// and the travel-range bias of the centre estimate (Takayama et al.).
// JS only gathers inputs, calls the core, draws and offers downloads.
import { h, numberField, selectField, table, downloadText, toCsv, dropZone, showError, fmt, fmtRes, fmtLimit, runState } from '../lib/ui.js';
import { polarChart, barChart, lineChart, xyChart } from '../lib/plot.js';

const UM = 1e-3; // mm per µm
const RAD = Math.PI / 180;

const REASON = { leadIn: 'lead-in', leadOut: 'lead-out', standstill: 'standstill', transient: 'transient', overshoot: 'overshoot', short: 'too short' };

/** What the core trimmed (trace.trimming), its time base, the feed and the centre used, in words. */
function trimNote(trace) {
  const t = trace.trimming;
  const parts = [];
  if (t) {
    const base = t.timeBase === 'column' ? "the file's time column" : 'the sample index (no time column: uniform sampling assumed)';
    const unit = t.timeBase === 'column' ? ' s' : '';
    const list = t.trimmed.map((s) => `${REASON[s.reason]} lines ${s.firstLine}–${s.lastLine} (${s.samples} samples, ${fmt(s.startTime, 3)}–${fmt(s.endTime, 3)}${unit}, ${fmt(s.startAngle / RAD, 1)}° to ${fmt(s.endAngle / RAD, 1)}°)`);
    const shown = list.slice(0, 8).join('; ') + (list.length > 8 ? `; and ${list.length - 8} more` : '');
    parts.push(`${t.applied ? 'Trimmed' : 'Found (not removed: trimming is off)'} to the constant-feed part, speeds within ±${fmt(t.band * 100, 0)} % of the plateau's median, time from ${base}: ${list.length ? shown : 'nothing trimmed'}.`);
  }
  parts.push(trace.feed === null ? 'Feed unknown.' : `Feed ${fmt(trace.feed, 0)} mm/min${t && t.timeBase === 'column' ? " (the plateau's median speed)" : ''}.`);
  if (trace.centre) {
    const c = trace.centre;
    parts.push(c.given
      ? `Deviations about the given centre (${fmt(c.point.x, 4)}, ${fmt(c.point.y, 4)}) mm.`
      : `Deviations about the trace's own least-squares centre (${fmt(c.point.x, 4)}, ${fmt(c.point.y, 4)}) mm, so its centre offset is 0 by construction.`);
  }
  return parts.join(' ');
}

/** A diagnostic at its 3-standard-error resolution: the value above it, else 0 and the resolution. */
function significant(v, res, unit, step = 0.01) {
  if (v === 0) return res < step ? `0 (below ${step} ${unit}, the display resolution)` : `0 (below ${fmtRes(res, step)} ${unit}, 3 standard errors)`;
  return `${fmtRes(v, step)} ${unit} (above ${fmtLimit(res, step)} ${unit}, 3 standard errors)`;
}

const CENTRE = {
  barPivot: 'from the bar’s pivot (the set-up offset)',
  given: 'from the given centre',
  traceLsc: '0 by construction: the deviations are about the trace’s own least-squares centre (give the programmed centre to measure it)',
};

/** "2:5, 3:3, 5:2.5" (order:amplitude µm[:phase deg]) → harmonics in mm/rad. */
function parseHarmonics(text) {
  const out = [];
  for (const part of text.split(/[,;\s]+/).filter(Boolean)) {
    const [o, a, p = '0'] = part.split(':');
    const order = Number(o);
    const amplitude = Number(a) * UM;
    const phase = Number(p) * RAD;
    if (!Number.isInteger(order) || order < 0 || !Number.isFinite(amplitude) || !Number.isFinite(phase)) {
      throw new Error(`harmonics: '${part}' is not order:amplitude[:phase], e.g. 2:5 or 3:3:90 (µm, degrees)`);
    }
    out.push({ order, amplitude, phase });
  }
  return out;
}

/**
 * @param {HTMLElement} root
 * @param {import('../lib/api.js').Api} api
 */
export async function mount(root, api) {
  // ---- inputs -------------------------------------------------------------
  const source = selectField({ label: 'Trace', id: 'ballbar-source', value: 'synthetic', options: [['synthetic', 'Synthetic (from the fields below)'], ['file', 'Loaded file']] });
  const f = {
    radius: numberField({ label: 'Bar length', unit: 'mm', value: 100, id: 'ballbar-radius', min: 1 }),
    range: numberField({ label: 'Travel range', unit: '°', value: 360, id: 'ballbar-range', min: 10, max: 360 }),
    offX: numberField({ label: 'Centre offset X (Z for a B axis)', unit: 'µm', value: 0, id: 'ballbar-offset-x' }),
    offY: numberField({ label: 'Centre offset Y (X for a B axis)', unit: 'µm', value: 10, id: 'ballbar-offset-y' }),
    feed: numberField({ label: 'Feed', unit: 'mm/min', value: 1000, id: 'ballbar-feed', min: 1 }),
    backlashX: numberField({ label: 'Backlash X', unit: 'µm', value: 0, id: 'ballbar-backlash-x' }),
    backlashY: numberField({ label: 'Backlash Y', unit: 'µm', value: 0, id: 'ballbar-backlash-y' }),
    servo: numberField({ label: 'Servo mismatch (X lags)', unit: 'ms', value: 0, id: 'ballbar-servo' }),
    squareness: numberField({ label: 'Squareness', unit: 'µrad', value: 0, id: 'ballbar-squareness' }),
    maxOrder: numberField({ label: 'Harmonics up to order', value: 10, id: 'ballbar-max-order', min: 2, max: 50, step: 1 }),
    tolerance: numberField({ label: 'G tolerance (ISO 230-4)', unit: 'µm; blank: none', value: '', id: 'ballbar-tolerance', min: 0, title: 'The circular deviation G allowed: each run is reported as pass or fail against it' }),
  };
  // The synthetic generator's fields describe no loaded file: they are
  // hidden (and so left out of the report) while a file is the trace.
  const SYNTHETIC = ['range', 'offX', 'offY', 'feed', 'backlashX', 'backlashY', 'servo', 'squareness'];
  const showSource = () => {
    const file = source.value === 'file';
    for (const k of SYNTHETIC) f[k].el.hidden = file;
    harmField.hidden = file;
  };
  source.input.addEventListener('change', showSource);
  const harm = h('input', { id: 'ballbar-harmonics-input', value: '2:5, 3:3, 5:2.5', title: 'order:amplitude µm[:phase °], comma-separated (sine convention: A·sin(nθ + φ))' });
  const harmField = h('label', { class: 'field' }, h('span', {}, 'Motion-error harmonics ', h('span', { class: 'unit' }, '[order:µm[:°]]')), harm);
  let loaded = null;
  const fileInfo = h('p', { id: 'ballbar-file-info', class: 'unit' }, 'No file loaded (CSV/TSV: angle + deviation, or X/Y).');
  // Reads the file with the column mapping `columns` (none: the core finds
  // its columns by their usual names).
  const load = async (text, name, columns) => {
    loaded = null;
    fileInfo.textContent = `${name}: reading…`;
    try {
      loaded = await api.call('parseBallbarTrace', [text, { nominalRadius: f.radius.value, ...(columns ? { columns } : {}) }]);
      const trimmed = loaded.trimming ? loaded.trimming.trimmed.length : 0;
      fileInfo.textContent = `${name}: ${loaded.runs.length} run(s), ${loaded.runs.map((r) => `${r.direction} ${r.angleRad.length} points`).join(', ')}${trimmed ? `; ${trimmed} stretch(es) trimmed (see the results)` : ''}`;
      source.value = 'file';
      showSource();
      await analyse();
    } catch (e) {
      notLoaded(e, name);
    }
  };
  // The core's layout preview and the column mapping: each menu starts at
  // the column the core reads for that role; the page guesses nothing.
  const mapBox = h('div', { id: 'ballbar-mapper' });
  const showMapper = async (text, name) => {
    mapBox.replaceChildren();
    let layout;
    try {
      layout = await api.call('traceLayout', [text, undefined, 'ballbar']);
    } catch {
      return; // parseBallbarTrace's error already says why
    }
    const columns = layout.columns.filter((c) => c.kind !== 'text');
    const pick = (role, label) => selectField({ label, id: `ballbar-map-${role}`, value: columns.find((c) => c.role === role)?.name || '', options: [['', '—'], ...columns.map((c) => [c.name, c.name])] });
    const m = { angle: pick('angle', 'angle'), deviation: pick('deviation', 'deviation'), x: pick('x', 'X'), y: pick('y', 'Y'), time: pick('time', 'time'), direction: pick('direction', 'direction') };
    const polar = columns.some((c) => c.role === 'angle') && columns.some((c) => c.role === 'deviation');
    const mode = selectField({ label: 'read as', id: 'ballbar-map-mode', value: polar ? 'polar' : 'xy', options: [['polar', 'angle + deviation'], ['xy', 'X/Y positions']] });
    const preview = table(['field', 'column', 'read as', 'unit', 'note'], layout.columns.map((c) => [c.field || '—', c.name, c.role ? `${c.kind}: ${c.role}` : c.kind, c.unit ?? '—', c.note ?? '']));
    preview.querySelector('table').id = 'ballbar-trace-layout';
    const read = h('button', { id: 'ballbar-map-read', onclick: () => {
      const keys = mode.value === 'polar' ? ['angle', 'deviation', 'time', 'direction'] : ['x', 'y', 'time', 'direction'];
      /** @type {Record<string, string>} */
      const mapping = {};
      for (const k of keys) if (m[k].value) mapping[k] = m[k].value;
      return load(text, name, mapping);
    } }, 'Read with these columns');
    mapBox.replaceChildren(
      h('p', { class: 'note', id: 'ballbar-trace-format' }, `Layout read: ${layout.format}; ${layout.notes.join('; ')}`),
      preview, h('div', { class: 'row' }, mode.el, ...Object.values(m).map((s) => s.el)), read);
  };
  const drop = dropZone({
    link: 'ballbar-trace',
    label: 'Drop a ball-bar trace (CSV/TSV, TwinCAT Scope export, SINUMERIK trace XML, halscope, MATLAB .mat capture) here, or click to choose one',
    accept: '.csv,.tsv,.txt,.dat,.xml,.mat',
    onText: async (text, name) => {
      await load(text, name);
      await showMapper(text, name);
    },
    // a .mat capture goes to the core as bytes, which reads it by its format
    onBytes: async (bytes, name) => {
      await load(bytes, name);
      await showMapper(bytes, name);
    },
    onRefused: (e, name) => {
      mapBox.replaceChildren();
      notLoaded(e, name);
    },
  });
  function notLoaded(e, name) {
    loaded = null;
    fileInfo.textContent = `${name}: not loaded (see the error below). No file loaded.`;
    source.value = 'synthetic';
    showSource();
    outUi.fail(e);
  }
  // A Renishaw .b5r report: the core reads its settings and features and
  // pairs them with ours; it carries no samples the core can read, so the
  // trace itself comes from the drop zone above (or the synthetic fields).
  let b5r = null;
  const b5rInfo = h('p', { id: 'ballbar-b5r-info', class: 'unit' }, 'No Renishaw report loaded (.b5r: its features are shown beside ours).');
  const b5rDrop = dropZone({
    id: 'ballbar-b5r-input',
    label: 'Drop a Renishaw Ballbar 20 report (.b5r) here to see its features beside ours, or click to choose one',
    accept: '.b5r,.xml',
    onText: async (text, name) => {
      b5r = null;
      try {
        const r = await api.call('readB5r', [text]);
        b5r = { text, name };
        const features = r.runs.reduce((n, x) => n + x.features.length, 0) + r.analyses.reduce((n, a) => n + a.features.length, 0);
        const settings = [r.testName, r.radius !== null ? `bar ${r.radius} mm` : null, r.feed !== null ? `F ${r.feed} mm/min` : null, r.plane ? `plane ${r.plane}` : null, r.runs.length ? `runs ${r.runs.map((x) => x.direction).join(', ')}` : null].filter(Boolean);
        b5rInfo.textContent = `${name}: ${settings.join('; ')}; ${features} feature(s). ${r.notes.join('; ')}${r.unread.length ? `; not read: ${r.unread.join(', ')}` : ''}`;
        await analyse();
      } catch (e) {
        b5rInfo.textContent = `${name}: not read (see the error below).`;
        outUi.fail(e);
      }
    },
    onRefused: (e, name) => {
      b5r = null;
      b5rInfo.textContent = `${name}: not read (see the error below).`;
      outUi.fail(e);
    },
  });
  const run = h('button', { id: 'ballbar-run', class: 'primary', dataset: { run: '' }, onclick: () => analyse() }, 'Analyse');
  const out = h('div', { id: 'ballbar-results' });
  const outUi = runState(out);

  // ---- alignment from the user's own sections -----------------------------
  // One trace per section (or one file whose runs are the sections). The
  // core reads every trace about one common centre (X/Y traces: the pivot or
  // programmed centre the user gives; angle/deviation traces: the bar's
  // pivot), fits each section's centre, the angle errors from two or more,
  // and the band around them (Takayama §2.1–2.2). Heights are required.
  const AXES = {
    b: { plane: ['Z', 'X'], along: 'Y', name: 'B' },
    a: { plane: ['Y', 'Z'], along: 'X', name: 'A' },
    c: { plane: ['X', 'Y'], along: 'Z', name: 'C' },
  };
  const al = {
    axis: selectField({ label: 'Rotary axis', id: 'align-axis', value: 'b', options: [['b', 'B (turns in Z–X, sections along Y)'], ['a', 'A (turns in Y–Z, sections along X)'], ['c', 'C (turns in X–Y, sections along Z)']], onChange: () => renderSections() }),
    radius: numberField({ label: 'Bar length', unit: 'mm', value: 100, id: 'align-radius', min: 1 }),
    centreP: numberField({ label: 'Common centre, first axis (X/Y traces)', unit: 'mm', value: '', id: 'align-centre-1', title: 'The pivot or the programmed circle centre, in the trace files\' X/Y coordinates; every section is read about it' }),
    centreQ: numberField({ label: 'Common centre, second axis (X/Y traces)', unit: 'mm', value: '', id: 'align-centre-2' }),
    maxOrder: numberField({ label: 'Harmonics considered up to order', value: 10, id: 'align-max-order', min: 1, max: 50, step: 1, title: 'The orders kept are those the data supports (BIC rule)' }),
  };
  let sections = []; // { name, text, run, layout, height: numberField }
  const secBox = h('div', { id: 'align-sections' });
  const alOut = h('div', { id: 'align-results' });
  const alUi = runState(alOut);
  const alInfo = h('p', { id: 'align-file-info', class: 'unit' }, 'No section loaded. Expected per file: a ball-bar trace (angle + deviation about the pivot, or X/Y in machine coordinates), the angle measured from the first plane axis.');
  const alDrop = dropZone({
    id: 'align-files',
    label: 'Drop one trace per section (two or more for the angle errors), or one file whose runs are the sections',
    accept: '.csv,.tsv,.txt',
    multiple: true,
    onRefused: (e, names) => sectionsRefused(e, names),
    onFiles: async (files) => {
      alUi.clear();
      sections = [];
      renderSections();
      try {
        const parsed = [];
        for (const { text, name } of files) {
          // A preview read (runs and layout); the estimate reads the text again about the common centre.
          const t = await api.call('parseBallbarTrace', [text, { nominalRadius: al.radius.value }]).catch((e) => {
            throw new Error(`${name}: ${(e && e.message) || e}`);
          });
          parsed.push({ name, text, t });
        }
        const layoutOf = (t) => (t.centre ? 'X/Y' : 'angle/deviation');
        // One file with several runs: each run is a section; else the first run of each file.
        const runs = parsed.length === 1 && parsed[0].t.runs.length > 1
          ? parsed[0].t.runs.map((r, k) => ({ name: `${parsed[0].name} run ${k + 1} (${r.direction.toUpperCase()})`, text: parsed[0].text, run: k, r, layout: layoutOf(parsed[0].t) }))
          : parsed.map(({ name, text, t }) => ({ name, text, run: 0, r: t.runs[0], layout: layoutOf(t) }));
        sections = runs.map((x, k) => ({
          name: x.name, text: x.text, run: x.run, layout: x.layout, points: x.r.angleRad.length,
          height: numberField({ label: `Height of ${x.name}`, unit: 'mm', value: '', id: `align-height-${k}` }),
        }));
        alInfo.textContent = `${sections.length} section(s): ${sections.map((x) => `${x.name} (${x.layout}, ${x.points} points)`).join(', ')}. Enter each section's height.`;
      } catch (e) {
        sectionsRefused(e, files.map((x) => x.name).join(', '));
      }
      renderSections();
    },
  });
  function sectionsRefused(e, names) {
    alInfo.textContent = `${names}: not loaded (see the error below). No section loaded.`;
    sections = [];
    renderSections();
    alUi.fail(e);
  }
  const alRun = h('button', { id: 'align-run', class: 'primary', onclick: () => estimate() }, 'Estimate alignment');
  function renderSections() {
    const ax = AXES[al.axis.value];
    al.centreP.el.querySelector('span').firstChild.textContent = `Common centre ${ax.plane[0]} (X/Y traces)`;
    al.centreQ.el.querySelector('span').firstChild.textContent = `Common centre ${ax.plane[1]} (X/Y traces)`;
    secBox.replaceChildren(...sections.map((x) => {
      x.height.el.querySelector('span').firstChild.textContent = `${ax.along} of ${x.name}`;
      return x.height.el;
    }));
  }

  async function estimate() {
    alUi.start();
    try {
      if (!sections.length) throw new Error('no section loaded: drop one ball-bar trace per section first');
      const ax = AXES[al.axis.value];
      for (const x of sections) if (!Number.isFinite(x.height.value)) throw new Error(`${ax.along} of ${x.name} [mm]: enter the section's height (no default: a wrong height gives a wrong angle error)`);
      const [cp, cq] = [al.centreP.value, al.centreQ.value];
      if (Number.isFinite(cp) !== Number.isFinite(cq)) throw new Error(`common centre: give both ${ax.plane[0]} and ${ax.plane[1]}, or neither`);
      const centre = Number.isFinite(cp) ? { x: cp, y: cq } : undefined;
      const input = {
        sections: sections.map((x) => ({ y: x.height.value, text: x.text, run: x.run })),
        radius: al.radius.value,
        maxOrder: al.maxOrder.value,
        ...(centre ? { centre } : {}),
      };
      const r = await api.call('estimateAlignmentBand', [input]);
      renderAlignment(r, ax, centre);
      alUi.ok();
    } catch (e) {
      alUi.fail(e);
    }
  }

  function renderAlignment(r, ax, centre) {
    const [p, q] = ax.plane;
    const um = (v) => fmtRes(v / UM, 0.01);
    // An offset the span cannot determine is said in words, never as ±10⁵ µm.
    const offset = (v, band, ok) => (ok ? `${um(v)} ± ${um(band)}` : 'not determined');
    const rows = r.estimate.sections.map((e, k) => {
      const b = r.sections[k];
      return [sections[k].name, fmt(e.y, 1), offset(e.z, b.bandZ, b.determinedZ), offset(e.x, b.bandX, b.determinedX),
        `${um(b.biasZ)} / ${um(b.biasX)}`, `${um(b.sigmaZ)} / ${um(b.sigmaX)}`, b.order < 2 ? 'none' : `2…${b.order}`, fmtRes(b.noise / UM, 0.01), fmt(b.rangeDeg, 1)];
    });
    const secTable = table(['section', `${ax.along} [mm]`, `offset ${p} [µm]`, `offset ${q} [µm]`, `bias ${p}/${q} [µm]`, `σ ${p}/${q} [µm]`, 'harmonics kept', 'noise [µm]', 'span [°]'], rows);
    secTable.querySelector('table').id = 'align-offsets';
    const notes = r.sections.filter((b) => b.note).map((b, k) => h('li', {}, `${sections[k].name}: ${b.note}`));
    const angleText = (v, g) => (g.determined ? `${fmtRes(v * 1e6, 0.01)} ± ${fmtRes(g.band * 1e6, 0.01)}` : 'not determined');
    const angle = r.estimate.deltaBz === null
      ? h('p', { id: 'align-angle' }, 'Angle errors: need two sections at different heights.')
      : h('p', { id: 'align-angle' },
          `Δ${ax.name}${p.toLowerCase()} = `, h('strong', { id: 'align-angle-1' }, angleText(r.estimate.deltaBz, r.bandBz)), ' µrad; ',
          `Δ${ax.name}${q.toLowerCase()} = `, h('strong', { id: 'align-angle-2' }, angleText(r.estimate.deltaBx, r.bandBx)), ' µrad (µm per m).');
    const about = centre
      ? `X/Y traces read about the common centre you gave (${p} ${fmt(centre.x, 3)} mm, ${q} ${fmt(centre.y, 3)} mm); angle/deviation traces about the bar's pivot.`
      : 'Every trace is angle/deviation, read about the bar\'s pivot.';
    const chart = h('div', { id: 'align-chart' });
    const csv = () => toCsv({
      section: sections.map((x) => JSON.stringify(x.name)),
      [`${ax.along.toLowerCase()}_mm`]: r.estimate.sections.map((e) => e.y),
      [`offset_${p.toLowerCase()}_um`]: r.estimate.sections.map((e) => e.z / UM),
      [`band_${p.toLowerCase()}_um`]: r.sections.map((b) => (b.determinedZ ? b.bandZ / UM : '')),
      [`offset_${q.toLowerCase()}_um`]: r.estimate.sections.map((e) => e.x / UM),
      [`band_${q.toLowerCase()}_um`]: r.sections.map((b) => (b.determinedX ? b.bandX / UM : '')),
      [`angle_${p.toLowerCase()}_urad`]: [r.estimate.deltaBz === null ? '' : r.estimate.deltaBz * 1e6],
      [`angle_band_${p.toLowerCase()}_urad`]: [r.bandBz === null || !r.bandBz.determined ? '' : r.bandBz.band * 1e6],
      [`angle_${q.toLowerCase()}_urad`]: [r.estimate.deltaBx === null ? '' : r.estimate.deltaBx * 1e6],
      [`angle_band_${q.toLowerCase()}_urad`]: [r.bandBx === null || !r.bandBx.determined ? '' : r.bandBx.band * 1e6],
    });
    const json = () => JSON.stringify({ axis: ax.name, plane: ax.plane, sectionsAlong: ax.along, units: { offsets: 'mm', heights: 'mm', angles: 'rad', spans: 'deg' }, inputs: { radius: al.radius.value, maxOrder: al.maxOrder.value, centre: centre ?? null, sections: sections.map((x, k) => ({ name: x.name, layout: x.layout, run: x.run, position: r.estimate.sections[k].y, points: x.points })) }, result: r }, null, 2);
    alOut.replaceChildren(
      h('p', { id: 'align-centre-used', class: 'unit' }, about),
      secTable,
      notes.length ? h('ul', { id: 'align-notes' }, ...notes) : '',
      angle,
      chart,
      h('p', { class: 'unit' }, `Band = |bias| + max|Δ|²/R + ${r.coverage}σ. The bias is the travel range's systematic error (Takayama §2.1) from the harmonics the data supports (BIC rule); σ is the noise's standard error, widened for correlated samples. A full revolution has no bias.`),
      h('div', { class: 'buttons' },
        h('button', { id: 'align-download-json', onclick: () => downloadText('alignment.json', json(), 'application/json') }, 'Download result (JSON)'),
        h('button', { id: 'align-download-csv', onclick: () => downloadText('alignment.csv', csv(), 'text/csv') }, 'Download result (CSV)')),
    );
    drawOffsets(chart, r, ax);
  }

  /** Offsets against height with their bands and the fitted lines (slope = the angle error). */
  function drawOffsets(el, r, ax) {
    const ys = r.estimate.sections.map((e) => e.y);
    const traces = [];
    const comps = [['z', 'Z', 'bandZ', 'determinedZ', 'interceptZ', 'deltaBz'], ['x', 'X', 'bandX', 'determinedX', 'interceptX', 'deltaBx']];
    comps.forEach(([key, , band, det, icpt, slope], c) => {
      const color = ['#0b6bcb', '#d9480f'][c];
      const name = ax.plane[c];
      traces.push({ x: ys, y: r.estimate.sections.map((e) => e[key] / UM), points: true, color, label: `offset ${name} [µm]` });
      r.sections.forEach((b, k) => {
        if (b[det]) traces.push({ x: [ys[k], ys[k]], y: [(r.estimate.sections[k][key] - b[band]) / UM, (r.estimate.sections[k][key] + b[band]) / UM], color });
      });
      if (r.estimate[slope] !== null) {
        const y0 = Math.min(...ys);
        const y1 = Math.max(...ys);
        traces.push({ x: [y0, y1], y: [y0, y1].map((y) => (r.estimate[icpt] + r.estimate[slope] * y) / UM), color, dash: [6, 4], label: `fit: slope ${fmtRes(r.estimate[slope] * 1e6, 0.01)} µrad` });
      }
    });
    xyChart(el, { traces, equal: false, xLabel: `${ax.along} [mm]`, yLabel: 'offset [µm]', title: 'Offsets against height, with bands and the fitted lines (slope = angle error)' });
  }

  // ---- paper examples -----------------------------------------------------
  const exName = selectField({ label: 'Paper figure', id: 'ballbar-example', value: 'fig7', options: [['fig6', 'Fig. 6: single harmonics, 180°'], ['fig7', 'Fig. 7: travel range 90…360°'], ['fig8', 'Fig. 8: four offset positions'], ['fig12', 'Fig. 12: angle error 10 µm/350 mm'], ['fig7-phased', 'Fig. 7 with phases 26°/25°/200° (reproduces X and Z)'], ['fig11', 'Fig. 11: measured trace, orders 2–3 only']] });
  const exReading = selectField({ label: 'Reading', id: 'ballbar-example-reading', value: '100', options: [['100', 'Ball bar, 100 mm (default)'], ['0', 'DBB5 centre ball (radius 0)']] });
  const exOut = h('div', { id: 'ballbar-example-results' });
  const exUi = runState(exOut);
  const exRun = h('button', { id: 'ballbar-example-run', onclick: () => example() }, 'Run example');

  const traceCard = h('div', { class: 'card' }, h('h3', {}, 'Trace'), h('div', { class: 'fields' }, source.el, ...Object.values(f).map((x) => x.el), harmField), drop, fileInfo, mapBox, b5rDrop, b5rInfo, run);
  const alCard = h('div', { class: 'card', id: 'align-card' }, h('h3', {}, 'Rotary-axis alignment from your sections (Takayama §2.2)'), h('div', { class: 'fields' }, ...Object.values(al).map((x) => x.el)), alDrop, alInfo, secBox, alRun, alOut);
  const exCard = h('div', { class: 'card' }, h('h3', {}, 'The paper’s simulations (Takayama et al., Figs. 6, 7, 8, 12)'), h('div', { class: 'fields' }, exName.el, exReading.el), exRun, exOut);
  // Results shown are marked outdated as soon as an input they came from is edited.
  outUi.dependsOn(traceCard);
  alUi.dependsOn(alCard);
  exUi.dependsOn(exCard);
  root.replaceChildren(traceCard, out, alCard, exCard);

  /** The .b5r report's features beside ours, as the core pairs them. */
  function besideCard(rows) {
    const num = (v, unit) => (v === null ? '—' : `${fmt(v, 4)}${unit ? ` ${unit}` : ''}`);
    const t = table(['reported in', 'feature', 'Renishaw (as written)', 'Renishaw in our unit', 'ours', 'line'],
      rows.map((r) => [r.source, r.feature, num(r.theirs, r.theirsUnit), num(r.theirsInOurs, r.oursUnit), r.oursUnit ? num(r.ours, r.oursUnit) : '— (not computed here)', String(r.line)]));
    t.querySelector('table').id = 'ballbar-b5r-beside';
    return h('div', { class: 'card' }, h('h3', {}, `Renishaw report beside ours (${b5r.name})`),
      h('p', { class: 'note' }, 'Each side in its own sign convention; a unit of another quantity is not converted. The report\'s raw samples are not read: ours come from the trace above.'), t);
  }

  async function getTrace() {
    if (source.value === 'file') {
      if (!loaded) throw new Error('no trace loaded: drop a CSV/TSV file, or choose "Synthetic"');
      return loaded;
    }
    return api.call('syntheticBallbarTrace', [{
      radius: f.radius.value,
      rangeDeg: f.range.value,
      feed: f.feed.value,
      offsetX: f.offX.value * UM,
      offsetY: f.offY.value * UM,
      harmonics: parseHarmonics(harm.value),
      backlashX: f.backlashX.value * UM,
      backlashY: f.backlashY.value * UM,
      servoMismatch: f.servo.value * 1e-3,
      squareness: f.squareness.value * 1e-6,
    }]);
  }

  async function analyse() {
    const token = outUi.start();
    try {
      const trace = await getTrace();
      const r0 = trace.nominalRadius;
      const first = trace.runs[0];
      const n = first.angleRad.length;
      const x = new Float64Array(n);
      const y = new Float64Array(n);
      for (let i = 0; i < n; i++) {
        const rr = r0 + first.deviation[i];
        x[i] = rr * Math.cos(first.angleRad[i]);
        y[i] = rr * Math.sin(first.angleRad[i]);
      }
      const [fit, harmonics, iso] = await Promise.all([
        api.call('fitCircle', [x, y]),
        api.call('harmonics', [first.angleRad, first.deviation, f.maxOrder.value]).catch((e) => e),
        api.call('circularTest', [trace]),
      ]);
      // Travel-range sweep of the fitted centre with the measured harmonics
      // (orders ≥ 2), as the paper's §4.1.4 does with its DBB5 trace.
      const motion = Array.isArray(harmonics) ? harmonics.filter((c) => c.order >= 2) : [];
      const ranges = Array.from({ length: 34 }, (_, k) => 30 + 10 * k);
      const sweep = await api.call('travelRangeSweep', [{ offset: { z: fit.cx, x: fit.cy }, harmonics: motion, ranges, radius: r0, samples: 1000 }]);
      const beside = b5r ? await api.call('b5rBeside', [b5r.text, trace]) : null;
      if (!outUi.current(token)) return;
      render(trace, fit, harmonics, iso, sweep, beside);
      outUi.ok();
    } catch (e) {
      if (outUi.current(token)) outUi.fail(e);
    }
  }

  function render(trace, fit, harmonics, iso, sweep, beside) {
    const r0 = trace.nominalRadius;
    // Polar plot: r = base + deviation (µm), base = 2 × the largest |deviation|.
    const all = trace.runs.flatMap((r) => Array.from(r.deviation, (d) => Math.abs(d) / UM));
    const base = Math.max(1, 2 * Math.max(...all));
    const traces = trace.runs.map((r) => ({ angle: r.angleRad, r: Float64Array.from(r.deviation, (d) => base + d / UM), label: `${r.direction.toUpperCase()} deviation (µm)` }));
    const circ = Float64Array.from({ length: 361 }, (_, i) => i * RAD);
    traces.push({ angle: circ, r: Float64Array.from(circ, (t) => base + ((fit.r - r0) + fit.cx * Math.cos(t) + fit.cy * Math.sin(t)) / UM), label: 'fitted circle', color: '#b3261e' });
    const polarEl = h('div', { id: 'ballbar-polar' });
    const barEl = h('div', { id: 'ballbar-harmonics' });
    const sweepEl = h('div', { id: 'ballbar-sweep' });
    // Pass/fail against the user's G tolerance, at the display resolution the G is shown with.
    const tol = f.tolerance.value;
    const verdict = (g) => (Number.isFinite(tol) ? (Number(fmtRes(g)) <= tol ? 'pass' : 'FAIL') : null);
    const isoRows = iso.runs.map((r) => [r.direction.toUpperCase(), fmtRes(r.gUm), ...(Number.isFinite(tol) ? [h('strong', { class: `verdict-${verdict(r.gUm)}` }, verdict(r.gUm))] : []), fmtRes(r.fMaxUm), fmtRes(r.fMinUm), fmtRes(r.centreXMm / UM), fmtRes(r.centreYMm / UM), fmt(r.spanDeg, 1)]);
    const d = iso.diagnostics;
    const diagRows = d
      ? [
          ['Centre offset X / Y (display resolution 0.01 µm)', d.centre === 'traceLsc' ? `0 / 0 µm, ${CENTRE.traceLsc}` : `${fmtRes(d.centreOffsetXUm)} / ${fmtRes(d.centreOffsetYUm)} µm ${CENTRE[d.centre]}`],
          ['Backlash X', significant(d.backlashXUm, d.backlashXResolutionUm, 'µm')],
          ['Backlash Y', significant(d.backlashYUm, d.backlashYResolutionUm, 'µm')],
          ['Servo mismatch (X lags Y)', d.servoMismatchMs === null ? '— (needs CCW + CW and the feed)' : significant(d.servoMismatchMs, d.servoMismatchResolutionMs, 'ms', 0.001)],
          ['Scale mismatch (X − Y)', significant(d.scaleMismatchPpm, d.scaleMismatchResolutionPpm, 'ppm')],
          ['Squareness (axes < 90° positive)', significant(d.squarenessUrad, d.squarenessResolutionUrad, 'µrad')],
          ['Cyclic error', d.cyclic ? `X ${fmtRes(d.cyclic.amplitudeXUm)} µm, Y ${fmtRes(d.cyclic.amplitudeYUm)} µm at ${fmt(d.cyclic.pitchMm, 2)} mm pitch (F ${fmt(d.cyclicTest.fRatio, 1)} above the critical ${fmt(d.cyclicTest.fCritical, 1)})` : d.cyclicTest ? `none: F ${fmt(d.cyclicTest.fRatio, 1)} not above the critical ${fmt(d.cyclicTest.fCritical, 1)} (α = 0.1 % over ${d.cyclicTest.pitches} pitches)` : '—'],
          ...d.reversalSpikes.map((s) => [`Reversal spike ${s.direction.toUpperCase()} ${s.axis.toUpperCase()} at ${s.angleDeg}°`, `${fmtRes(s.heightUm)} µm (threshold ${fmtLimit(s.thresholdUm)} µm)`]),
          ['Reversal spikes', d.reversalSpikes.length ? `reported above ${fmtLimit(d.spikeThresholdUm)} µm (1.5 × the largest residual away from the quadrant points, the largest over the runs)` : `none above the trace's noise threshold of ${fmtLimit(d.spikeThresholdUm)} µm`],
          ['Run-model residual RMS (fit quality)', `${fmtLimit(d.residualRmsUm)} µm (the noise the standard errors rest on)`],
        ]
      : [['Diagnostics', 'need a run over a full revolution']];
    const isoTable = table(['run', 'G [µm]', ...(Number.isFinite(tol) ? [`G ≤ ${fmtRes(tol)} µm`] : []), 'F max [µm]', 'F min [µm]', 'LSC centre X [µm]', 'LSC centre Y [µm]', 'span [°]'], isoRows);
    isoTable.querySelector('table').id = 'ballbar-iso';
    const diagTable = table(['diagnostic', 'value'], diagRows);
    diagTable.querySelector('table').id = 'ballbar-diagnostics';
    const downloads = h('div', { class: 'buttons' },
      h('button', { id: 'ballbar-download', onclick: () => downloadText('ballbar-results.json', JSON.stringify({ fit, harmonics: Array.isArray(harmonics) ? harmonics : String(harmonics.message), iso, travelRangeSweep: sweep }, null, 2), 'application/json') }, 'Download results (JSON)'),
      h('button', { id: 'ballbar-download-sweep', onclick: () => downloadText('travel-range-sweep.csv', toCsv({ rangeDeg: sweep.map((p) => p.rangeDeg), errorZUm: sweep.map((p) => p.errorZ / UM), errorXUm: sweep.map((p) => p.errorX / UM) }), 'text/csv') }, 'Download sweep (CSV)'),
      h('button', { id: 'ballbar-download-trace', onclick: () => {
        const cat = (fn) => trace.runs.flatMap((r) => Array.from(r.angleRad, (_, i) => fn(r, i)));
        downloadText('ballbar-trace.csv', toCsv({ angle_deg: cat((r, i) => r.angleRad[i] / RAD), deviation_um: cat((r, i) => r.deviation[i] / UM), direction: cat((r) => (r.direction === 'ccw' ? 1 : -1)) }), 'text/csv');
      } }, 'Download trace (CSV)'),
    );
    const warnings = trace.warnings && trace.warnings.length ? h('ul', { id: 'ballbar-warnings', class: 'error-box' }, trace.warnings.map((w) => h('li', {}, w))) : null;
    out.replaceChildren(
      h('div', { class: 'card' }, h('h3', {}, 'Trace'), h('p', { id: 'ballbar-trim' }, trimNote(trace)), warnings),
      h('div', { class: 'card' }, h('h3', {}, 'Fitted centre (least-squares circle of the first run)'),
        h('p', {}, 'Centre X ', h('strong', { id: 'ballbar-centre-x' }, fmtRes(fit.cx / UM, 0.001)), ' µm, Y ', h('strong', { id: 'ballbar-centre-y' }, fmtRes(fit.cy / UM, 0.001)), ' µm; radius ', fmtRes(fit.r, 0.000001), ' mm; RMS residual ', fmtRes(fit.rmsResidual / UM, 0.001), ' µm (display resolution 0.001 µm)'),
        polarEl),
      h('div', { class: 'card' }, h('h3', {}, 'Harmonics of the deviation (least squares, valid on partial ranges)'), barEl),
      h('div', { class: 'card' }, h('h3', {}, 'Travel-range bias of the centre estimate (Takayama §2.1 with these harmonics)'), sweepEl),
      h('div', { class: 'card' }, h('h3', {}, 'ISO 230-4 circular test'), isoTable, h('p', {}, 'Circular hysteresis H: ', h('strong', { id: 'ballbar-h' }, iso.hUm === null ? '— (needs CCW and CW)' : `${fmtRes(iso.hUm)} µm`), ' (µm values shown to 0.01 µm; smaller magnitudes read 0)'), diagTable, downloads),
      ...(beside ? [besideCard(beside)] : []),
    );
    polarChart(polarEl, { title: `Deviation [µm], magnified (rings labelled with the deviation; 0 = nominal circle)`, rOffset: base, traces, circles: [{ r: base, label: 'nominal' }], markers: [{ x: fit.cx / UM, y: fit.cy / UM, label: 'fitted centre' }] });
    if (Array.isArray(harmonics)) {
      const hs = harmonics.filter((c) => c.order >= 1);
      barChart(barEl, { title: 'Amplitude by order (order 1 = centre offset)', labels: hs.map((c) => c.order), values: hs.map((c) => c.amplitude / UM), yLabel: 'µm' });
    } else {
      showError(barEl, harmonics);
    }
    lineChart(sweepEl, {
      title: 'Estimated − true centre against travel range',
      xLabel: 'travel range [°]',
      yLabel: 'µm',
      series: [{ label: 'ΔZ (X) error' }, { label: 'ΔX (Y) error' }, { label: '|error|', dash: [6, 4] }],
      data: [sweep.map((p) => p.rangeDeg), sweep.map((p) => p.errorZ / UM), sweep.map((p) => p.errorX / UM), sweep.map((p) => Math.hypot(p.errorZ, p.errorX) / UM)],
      bands: [
        { from: 75, to: 105, label: 'universal head ~90°', color: 'rgba(217,72,15,0.10)' },
        { from: 160, to: 200, label: 'trunnion ~180°', color: 'rgba(11,107,203,0.10)' },
        { from: 330, to: 360, label: 'table-on-table ~360°', color: 'rgba(43,138,62,0.12)' },
      ],
    });
  }

  async function example() {
    exUi.start();
    try {
      const ex = await api.call('ballbarExample', [exName.value, Number(exReading.value)]);
      const paper = table(['quantity', 'range [°]', 'paper', 'ours'], ex.paper.map((p) => [p.label, p.rangeDeg || '—', p.paper, fmt(p.ours, 2)]));
      paper.querySelector('table').id = 'ballbar-paper-table';
      const chartEl = h('div', { id: 'ballbar-example-chart' });
      // paper / ours / why (docs/readings.md)
      const why = {
        fig6: 'Why 0.15, not ≈ 0.25: the ball bar gives at most 0.15 for any common phase; the DBB5 reading (radius 0) reaches the paper’s ratio.',
        fig7: 'Why Z = 0: with all phases 0 the ball-bar locus is symmetric about Z. “Fig. 7 with phases” reproduces X and Z within 0.3 µm.',
        'fig7-phased': 'Why these phases (26°, 25°, 200°): a grid search for the paper’s four numbers; the paper itself says “all phases 0°”, which cannot give its Z.',
        fig8: 'Why every offset gives the same value: the ball-bar reading is translation invariant; DBB5 (radius 0) depends on the offset.',
        fig11: 'Why below the paper at 150° and 180°: the text quotes only orders 2 and 3 (1.3 and 2.7 µm) of the measured trace; with the phases that bias most they give 21 / 11 / 7 µm. The rest of the paper’s 15 and 11 µm comes from orders 4–10, which are in Fig. 10 only.',
        fig12: 'Why ≈ 0 with the ball bar: a motion error common to both sections cancels in the angle estimate; DBB5 gives the paper’s order for ΔBz only.',
      }[ex.name];
      exOut.replaceChildren(h('p', {}, ex.description), paper, ...(why ? [h('p', { class: 'note' }, why)] : []), chartEl);
      exUi.ok();
      if (ex.angle.length) {
        lineChart(chartEl, { title: 'Angle-error estimate error', xLabel: 'travel range [°]', yLabel: 'µm / 700 mm', series: [{ label: 'ΔBz' }, { label: 'ΔBx' }], data: [ex.angle.map((p) => p.rangeDeg), ex.angle.map((p) => (p.errorBz * 700) / UM), ex.angle.map((p) => (p.errorBx * 700) / UM)] });
      } else if (ex.name === 'fig6') {
        const pts = ex.curves[0].points;
        barChart(chartEl, { title: '|centre error| by harmonic order (180°)', labels: pts.map((p) => p.rangeDeg), values: pts.map((p) => Math.hypot(p.errorZ, p.errorX) / UM), yLabel: 'µm' });
      } else {
        const xs = ex.curves[0].points.map((p) => p.rangeDeg);
        lineChart(chartEl, {
          title: 'Radial centre error against travel range',
          xLabel: 'travel range [°]',
          yLabel: 'µm',
          series: ex.curves.map((c) => ({ label: `offset (${fmt(c.offset.z / UM, 0)}, ${fmt(c.offset.x / UM, 0)}) µm` })),
          data: [xs, ...ex.curves.map((c) => c.points.map((p) => Math.hypot(p.errorZ, p.errorX) / UM))],
        });
      }
    } catch (e) {
      exUi.fail(e);
    }
  }

  await analyse();
}
