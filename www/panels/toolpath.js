// Tool-path panel (qiu §4-1 to §4-3): paste or load an NC program, simulate
// the NC acc/dec + servo lag, see where the tool leaves the path, and
// download a reverse-compensated program. All computation is in the core
// (simulateToolPath, reverseCompensate, toolpathExample); this file only
// gathers inputs, calls the API and draws.
import { h, numberField, selectField, table, downloadText, dropZone, fmt, toCsv, runState, progressBar, showError, cancelGuard } from '../lib/ui.js';
import { lineChart } from '../lib/plot.js';
import { programFiles } from './toolpath-files.js';
import { ncEditor } from '../lib/editor.js';
import { pathView } from '../lib/path3d.js';
import { unpackSimulation } from '../lib/derived.js';
import { worstSegments, marksOf, worstLists } from './toolpath-worst.js';

/**
 * @param {HTMLElement} root
 * @param {import('../lib/api.js').Api} api
 */
export async function mount(root, api) {
  const examples = {
    arcs: await api.call('toolpathExample', ['arcs']),
    lines: await api.call('toolpathExample', ['lines']),
  };
  // The program editor (CodeMirror); `nc` is its textarea handle (value,
  // selection, input/change events), as the page and its tests know it.
  const editor = ncEditor({ id: 'toolpath-nc', onLine: (n) => view3d.highlightLine(n) });
  const nc = editor.handle;
  // Program check: errors or warnings next to the text, each a
  // link that selects its line; the summary the user checks first.
  const check = h('div', { id: 'toolpath-check', 'aria-live': 'polite', style: 'max-height:330px;overflow:auto;font-size:90%' });
  const selectLine = (line) => editor.selectLine(line);
  // Cutter compensation: the tool radius per D is a text the core reads
  // ("D1=3, D8=0.25", program units); the summary says, per G41/G42
  // stretch, whether the path is offset or the programmed one.
  const radii = h('input', { type: 'text', id: 'toolpath-radii', placeholder: 'e.g. D1=3, D8=0.25', size: 22, title: 'Tool radius per D number for G41/G42, in program units' });
  const radiiField = h('label', { class: 'field' }, h('span', {}, 'Tool radii per D (G41/G42)'), radii);
  const radiiOption = () => (radii.value.trim() ? { toolRadii: radii.value } : undefined);
  radii.addEventListener('change', () => { programChanged(); checkProgram(); });
  /** The summary's cutter-compensation lines (none without G41/G42). */
  const cutterNote = (stretches) => stretches.length ? [h('ul', { id: 'toolpath-cutter' }, ...stretches.map((c) => h('li', {},
    `${c.code}${c.d ? ` ${c.d}` : ''} (${c.file ? `${c.file}, ` : ''}line ${c.line}): `,
    c.radius === null
      ? h('strong', {}, 'simulated path = programmed (un-offset) path; contour errors are those of the programmed path (no tool radius: see the warning)')
      : `offset tool-centre path computed with tool radius ${fmt(c.radius, 5)} mm`)))] : [];
  const lineLink = (w, cls) => w.file ? h('li', { class: cls }, `${w.file}, line ${w.line}, column ${w.column}: ${w.message}`) : h('li', { class: cls },
    h('a', { href: '#', class: 'nc-line', 'data-line': w.line, onclick: (e) => { e.preventDefault(); selectLine(w.line); } }, `line ${w.line}, column ${w.column}`),
    `: ${w.message}`);
  // A program file over STREAM_FROM bytes is never one string on the page:
  // the worker reads it in chunks into the core's NcStream (checkNcFile,
  // simulateNcFilePacked), and the editor shows its first HEAD_BYTES only,
  // read-only, with a note. 8 MiB: about 250,000 lines of a CAM finishing
  // post; the 35k-line cameo (1.1 MB) stays in the editor, editable.
  const STREAM_FROM = 8 << 20;
  const HEAD_BYTES = 16 << 10;
  /** The program read from its file in chunks: { file, name }, or null
   * when the program is the editor's text. */
  let bigFile = null;
  const bigNote = h('p', { class: 'note', id: 'toolpath-big-note', hidden: true });
  /** Back to the editor's own text (an example, a smaller file). */
  const leaveBigFile = () => {
    bigFile = null;
    bigNote.hidden = true;
    editor.setReadOnly(false);
  };
  const mb = (bytes) => `${fmt(bytes / 1e6, 3)} MB`;
  let checkSeq = 0;
  /** Checks the program in the text area (or the large file read in
   * chunks); `known` is a check of that same program already made (a
   * dropped file is checked before it is shown). */
  async function checkProgram(known) {
    const seq = ++checkSeq;
    try {
      const c = known ?? (bigFile
        ? await api.call('checkNcFile', [bigFile.file, radiiOption()])
        : await api.call('checkNc', [nc.value, files.options(radiiOption())]));
      if (seq !== checkSeq) return;
      // the editor holds the head only: no marks piled on its last line
      editor.showCheck(bigFile ? null : c);
      if (c.errors.length) {
        check.replaceChildren(
          h('p', { class: 'error' }, `${c.errors.length}${c.truncated ? '+' : ''} error(s): the program cannot be simulated until they are fixed.`),
          h('ul', { id: 'toolpath-check-errors' }, ...c.errors.map((w) => lineLink(w, 'error'))),
        );
        return;
      }
      const s = c.summary;
      const box = s.bboxMin ? `X ${fmt(s.bboxMin[0], 4)} … ${fmt(s.bboxMax[0], 4)}, Y ${fmt(s.bboxMin[1], 4)} … ${fmt(s.bboxMax[1], 4)}, Z ${fmt(s.bboxMin[2], 4)} … ${fmt(s.bboxMax[2], 4)} mm` : '—';
      const groups = s.warnings.map((g) => h('details', {},
        h('summary', {}, `${g.kind} (${g.count})`),
        h('ul', {}, ...g.indices.map((i) => lineLink(c.warnings[i], 'warn')))));
      check.replaceChildren(
        table(['program summary', ''], [
          ['bounding box', box],
          ['path length (cutting)', `${fmt(s.totalLength, 5)} mm (${fmt(s.cuttingLength, 5)} mm)`],
          ['arcs / lines / rapids / dwells', `${s.arcs} / ${s.lines} / ${s.rapids} / ${s.dwells}`],
          ['units, arc planes', `${s.units}${s.planes.length ? `, ${s.planes.join(' ')}` : ''}`],
          ['estimated motion time', h('span', {}, h('span', { id: 'toolpath-check-time' }, fmt(s.motionTime, 5)), ` s (Σ length/feed, rapids at ${s.rapidFeed} mm/min, no acc/dec)`)],
        ]),
        ...cutterNote(s.cutterCompensation),
        c.warnings.length ? h('div', { id: 'toolpath-check-warnings' }, h('p', {}, `${c.warnings.length} warning(s), by kind:`), ...groups) : h('p', {}, 'No warnings.'),
      );
    } catch (e) {
      if (seq === checkSeq) { check.replaceChildren(); showError(check, e); }
    }
  }
  let checkTimer = 0;
  nc.addEventListener('input', () => { clearTimeout(checkTimer); checkTimer = setTimeout(() => checkProgram(), 400); });
  nc.value = examples.arcs;
  let fileName = 'program.nc';
  const example = selectField({
    label: 'Built-in example', id: 'toolpath-example', value: 'arcs',
    options: [['arcs', 'Fig. 2-like path, B–D as 43 arcs'], ['lines', 'Fig. 2-like path, B–D as 83 lines']],
    onChange: (v) => { files.clear(); leaveBigFile(); nc.value = examples[v]; fileName = `example-${v}.nc`; programChanged(); checkProgram(); },
  });
  // Every dropped file is checked first: one the core does not read at all
  // (over its text budget, or not a text file: a PNG dropped on the program
  // replaced it with binary text and 100+ errors) is refused, and the
  // program in the text area stays as it was.
  const takeProgram = async (text, name) => {
    let known;
    let problem = null;
    try {
      known = await api.call('checkNc', [text, files.options(radiiOption())]);
      if (known.notRead) problem = known.errors[0].message;
    } catch (e) {
      problem = e instanceof Error ? e.message : String(e);
    }
    if (problem) {
      showError(check, new Error(`${name} was not loaded: ${problem}. The program shown is unchanged.`));
      return;
    }
    leaveBigFile();
    nc.value = text;
    fileName = name;
    programChanged();
    checkProgram(known);
  };
  /** A program file over STREAM_FROM: checked in the worker as it is read
   * in chunks (progress in the check area), then its head shown. */
  const takeProgramFile = async (file, name) => {
    const seq = ++checkSeq;
    const reading = h('p', { id: 'toolpath-reading' }, `Reading ${name} (${mb(file.size)}) in the worker…`);
    check.replaceChildren(reading);
    let known;
    let problem = null;
    try {
      known = await api.call('checkNcFile', [file, radiiOption()], {
        onProgress: (f) => { reading.textContent = `Reading ${name} (${mb(file.size)}) in the worker: ${Math.round(f * 100)} %`; },
      });
      if (known.notRead) problem = known.errors[0].message;
    } catch (e) {
      problem = e instanceof Error ? e.message : String(e);
    }
    if (seq !== checkSeq) return;
    if (problem) {
      check.replaceChildren();
      showError(check, new Error(`${name} was not loaded: ${problem}. The program shown is unchanged.`));
      return;
    }
    const head = await file.slice(0, HEAD_BYTES).text();
    const shown = head.slice(0, head.lastIndexOf('\n') + 1);
    const lines = shown.split('\n').length - 1;
    bigFile = { file, name };
    editor.setReadOnly(true);
    nc.value = shown;
    bigNote.textContent = `${name} is ${mb(file.size)}: a program over ${mb(STREAM_FROM)} is read in chunks by the worker, checked and simulated from the file, never as one text on the page. The editor shows its first ${lines.toLocaleString('en')} lines only, read-only; compensation is not offered for it. Choose an example or drop a smaller file to edit a program.`;
    bigNote.hidden = false;
    fileName = name;
    programChanged();
    checkProgram(known);
  };
  const files = programFiles(api, { onMain: takeProgram, onMainFile: takeProgramFile, onRefused: (e) => showError(check, e) });
  const drop = dropZone({ label: 'Drop an NC program (with its subprogram files, if any) here, or click to choose', accept: '.nc,.txt,.tap,.ngc,.cnc,.iso', multiple: true, largeFrom: STREAM_FROM, onFiles: files.take, onRefused: (e) => showError(check, e), id: 'toolpath-file' });
  const tA = numberField({ label: 'tA (acc/dec)', value: 40, unit: 'ms', step: 1, min: 0, id: 'toolpath-ta' });
  const tx = numberField({ label: 'T X', value: 15, unit: 'ms', step: 1, min: 0, id: 'toolpath-tx' });
  const ty = numberField({ label: 'T Y', value: 15, unit: 'ms', step: 1, min: 0, id: 'toolpath-ty' });
  const tz = numberField({ label: 'T Z', value: 15, unit: 'ms', step: 1, min: 0, id: 'toolpath-tz' });
  const ovr = numberField({ label: 'Feed override', value: 100, unit: '%', step: 5, min: 1, id: 'toolpath-override' });
  const dt = numberField({ label: 'Sampling dt', value: 1, unit: 'ms', step: 0.1, min: 0.01, id: 'toolpath-dt' });
  const magLabel = h('span', { id: 'toolpath-mag-value' }, '×200');
  const mag = h('input', { type: 'range', id: 'toolpath-mag', min: 1, max: 2000, step: 1, value: 200, title: 'error magnification' });
  const run = h('button', { id: 'toolpath-run', class: 'primary', dataset: { run: '' } }, 'Simulate');
  const comp = h('button', { id: 'toolpath-compensate' }, 'Compensate');
  const cancel = h('button', { id: 'toolpath-cancel', hidden: true }, 'Cancel');
  const budget = numberField({ label: 'Time budget', value: 5, unit: '%', step: 1, min: 0, id: 'toolpath-budget' });
  // The lines to compensate (fromLine, toLine): the text's own line
  // numbers, blank for the first and the last; the core checks them.
  const fromLine = numberField({ label: 'Compensate from line', value: '', step: 1, min: 1, id: 'toolpath-from', title: 'fromLine: the first line to compensate (blank: the first); lines outside stay as written' });
  const toLine = numberField({ label: 'to line', value: '', step: 1, min: 1, id: 'toolpath-to', title: 'toLine: the last line to compensate, inclusive (blank: the last)' });
  /** The line range of the compensation: only the ends given. */
  const lineRange = () => ({
    ...(fromLine.input.value.trim() === '' ? {} : { fromLine: fromLine.value }),
    ...(toLine.input.value.trim() === '' ? {} : { toLine: toLine.value }),
  });
  const compProgress = progressBar();
  const compRun = cancelGuard(cancel, compProgress);
  // A long program simulates for seconds: progress and Cancel, as for
  // reverse compensation.
  const simCancel = h('button', { id: 'toolpath-sim-cancel', hidden: true }, 'Cancel');
  const simProgress = progressBar();
  const simRun = cancelGuard(simCancel, simProgress);
  const out = h('div', { id: 'toolpath-out' });
  const pathBox = h('div', { class: 'plot', id: 'toolpath-path' });
  // The 3D path view (one WebGL context for the panel's life): a click on
  // the path or a mark selects its line in the editor; a new simulation
  // starts at the automatic magnification.
  const view3d = pathView({
    onPick: (line) => editor.selectLine(line, { focus: false }),
    onMagnification: (k) => {
      mag.value = String(Math.min(k, Number(mag.max)));
      magLabel.textContent = `×${k} (auto)`;
    },
  });
  const velBox = h('div', { class: 'plot', id: 'toolpath-velocity' });
  // The compensation's before/after in a 3D view of its own (a second
  // WebGL context for the panel's life): one simulation at a time, flipped
  // by the switch with the camera kept, on one colour scale; both measured
  // against the original program's path.
  const compView = pathView({
    prefix: 'toolpath-comp',
    height: 420,
    onPick: (line) => editor.selectLine(line, { focus: false }),
    onMagnification: (k) => {
      mag.value = String(Math.min(k, Number(mag.max)));
      magLabel.textContent = `×${k} (auto)`;
    },
  });
  const whichRadio = (value, label) => h('label', {}, h('input', { type: 'radio', name: 'toolpath-comp-which', id: `toolpath-comp-${value}`, value, checked: value === 'after', onchange: () => showComp(true) }), ` ${label}`);
  const compWhich = h('div', { class: 'path3d-bar', role: 'radiogroup', 'aria-label': 'simulation shown' }, 'Show: ', whichRadio('before', 'before (original program)'), whichRadio('after', 'after (compensated program, against the original path)'));
  const compOut = h('div', { id: 'toolpath-comp-out' });
  // One run state per result area; a new program empties both (its results
  // would belong to the previous program).
  const simUi = runState(out, pathBox, velBox);
  const compUi = runState(compOut);
  const programChanged = () => {
    last = null;
    lastComp = null;
    simUi.clear();
    compUi.clear();
  };
  nc.addEventListener('input', programChanged);

  /** @returns {import('../pkg/mtmotion.js').ToolPathConfig} */
  const cfg = () => ({
    tA: tA.value / 1e3,
    T: [tx.value / 1e3, ty.value / 1e3, tz.value / 1e3],
    dt: dt.value / 1e3,
    feedOverride: ovr.value / 100,
  });

  // Drawing only: the velocity chart gets at most this many points (every
  // stride-th sample). The numbers (tables, maximum, CSV) always use every
  // sample; the paths are drawn by the 3D views (lib/path3d.js).
  const MAX_DRAWN = 20000;
  /** Every stride-th value, so a plot gets at most MAX_DRAWN points (drawing only). */
  function thinned(a) {
    const stride = Math.max(1, Math.ceil(a.length / MAX_DRAWN));
    if (stride === 1) return a;
    const kept = new Float64Array(Math.ceil(a.length / stride));
    for (let i = 0, j = 0; i < a.length; i += stride, j++) kept[j] = a[i];
    return kept;
  }
  let last = null;
  /** The last compensation and the original program's pieces (null: none shown). */
  let lastComp = null;
  let compPieces = null;
  function redraw() {
    const k = Number(mag.value);
    magLabel.textContent = `×${k}`;
    if (last) view3d.setMagnification(k);
    if (lastComp) compView.setMagnification(k);
  }

  /** Shows the compensation's before or after simulation (the switch) in
   * its 3D view, on the scale 0 … the larger cutting maximum of the two;
   * `flip`: the other one of the same compensation (camera kept). */
  function showComp(flip = false) {
    if (!lastComp) return Promise.resolve();
    const c = lastComp;
    const after = /** @type {HTMLInputElement} */ (compWhich.querySelector('#toolpath-comp-after')).checked;
    const s = after ? c.afterSim : c.beforeSim;
    const scaleUm = Math.max(c.beforeSim.maxErrorUm, c.afterSim.maxErrorUm);
    compView.el.dataset.showing = after ? 'after' : 'before';
    return compView.show({ program: compPieces, sim: s, scaleUm, marks: marksOf(s, worstSegments(s).cutting, compPieces) }, { keepView: flip });
  }
  mag.addEventListener('input', redraw);

  async function simulate() {
    const token = simUi.start();
    const abort = simRun.start();
    try {
      // The program's segments (the core's parseNc reading) draw the
      // programmed path; not for a large file read in chunks (the
      // simulated path is drawn, coloured by its error).
      const parsed = bigFile ? Promise.resolve(null) : api.call('programPieces', [nc.value, files.options(radiiOption())]).catch(() => null);
      const onProgress = (f, stage = 'simulating') => {
        simCancel.hidden = false;
        simProgress.set(f, `${stage}: ${Math.round(f * 100)} %`);
      };
      const packed = bigFile
        ? await api.call('simulateNcFilePacked', [bigFile.file, { ...cfg(), ...radiiOption() }], { signal: abort.signal, onProgress })
        : await api.call('simulateToolPathPacked', [nc.value, files.options({ ...cfg(), ...radiiOption() })], { signal: abort.signal, onProgress });
      const s = unpackSimulation(packed);
      if (!simUi.current(token)) return;
      const program = await parsed;
      if (!simUi.current(token)) return;
      last = s;
      if (!(await showSimulation(s, program, token))) return;
      simUi.ok();
    } catch (e) {
      last = null;
      if (simUi.current(token)) simRun.failed(abort, e, simUi, 'Simulation');
    } finally {
      simRun.finish(abort);
    }
  }

  /** The charts, table, warnings and CSV button of one simulation, in
   * tasks of their own (false: a newer state came meanwhile). */
  async function showSimulation(s, program, token) {
    const later = async () => {
      await new Promise((r) => setTimeout(r, 0));
      return simUi.current(token);
    };
    // Not in the task that received the result (its copy is long enough).
    if (!(await later())) return false;
    const pieces = program;
    const warn = s.warnings.length
      ? h('details', { class: 'warn-box' }, h('summary', {}, `${s.warnings.length} warning(s)`), h('ul', {}, ...s.warnings.map((w) => h('li', {}, `${w.file ? `${w.file}, ` : ''}line ${w.line}, column ${w.column}: ${w.message}`))))
      : '';
    const thinnedNote = s.seriesStride > 1
      ? h('p', { class: 'note', id: 'toolpath-series-note' }, `${s.samples.toLocaleString('en')} samples simulated; the plots and the CSV keep the sample with the largest error of each ${s.seriesStride} (${s.t.length.toLocaleString('en')} rows). Every number above uses all samples.`)
      : '';
    const worst = worstSegments(s);
    if (!(await later())) return false;
    pathBox.replaceChildren(h('div', { class: 'chart-title' }, 'Programmed and simulated path in 3D (colour: contour error µm)'), view3d.el);
    velBox.replaceChildren();
    await view3d.show({ program: pieces, sim: s, scaleUm: s.maxErrorUm, marks: marksOf(s, worst.cutting, pieces) });
    if (!(await later())) return false;
    lineChart(velBox, { title: 'Axis velocity', xLabel: 't s', yLabel: 'mm/s', series: [{ label: 'X commanded', dash: [4, 4] }, { label: 'Y commanded', dash: [4, 4] }, { label: 'X simulated' }, { label: 'Y simulated' }], data: [s.t, s.velCmdX, s.velCmdY, s.velSimX, s.velSimY].map(thinned), height: 260 });
    // The numbers last, in the task that ends the run (the caller's ok()):
    // a run is done when its table shows.
    if (!(await later())) return false;
    out.replaceChildren(
      table(['quantity', 'value'], [
        ['maximum contour error', h('span', { id: 'toolpath-max-error' }, `${fmt(s.maxErrorUm, 4)} µm`)],
        ['at line / time', `${s.maxErrorLine} / ${fmt(s.maxErrorTime, 4)} s`],
        ['motion time', h('span', { id: 'toolpath-motion-time' }, `${fmt(s.motionTime, 5)} s`)],
        ['nominal time (Σ length / feed)', `${fmt(s.nominalTime, 5)} s`],
      ]),
      thinnedNote,
      warn,
      worstLists(worst, (line) => {
        editor.selectLine(line);
        view3d.highlightLine(line);
      }),
      h('button', { id: 'toolpath-csv', onclick: () => downloadText('toolpath-simulation.csv', toCsv({ t_s: s.t, cmd_x_mm: s.cmdX, cmd_y_mm: s.cmdY, cmd_z_mm: s.cmdZ, sim_x_mm: s.simX, sim_y_mm: s.simY, sim_z_mm: s.simZ, vel_x_mm_s: s.velSimX, vel_y_mm_s: s.velSimY, vel_z_mm_s: s.velSimZ, error_um: s.errorUm }), 'text/csv') }, 'Download CSV'),
    );
    return true;
  }

  async function compensate() {
    if (bigFile) {
      compUi.clear();
      showError(compOut, new Error(`reverse compensation reads the program as one text and writes it again: it is not offered for ${bigFile.name}, read in chunks (over ${mb(STREAM_FROM)})`));
      return;
    }
    const token = compUi.start();
    const abort = compRun.start();
    cancel.hidden = false;
    compProgress.set(0, 'starting');
    try {
      // The original program's segments (parseNc, as reverseCompensate
      // reads it) draw the programmed path; both simulations' samples map
      // to them (sampleSegment).
      const parsed = api.call('programPieces', [nc.value]).catch(() => null);
      const c = await api.call('reverseCompensate', [nc.value, { ...cfg(), timeBudget: budget.value / 100, ...lineRange() }], {
        signal: abort.signal,
        onProgress: (f, stage) => compProgress.set(f, stage),
      });
      if (!compUi.current(token)) return;
      const pieces = await parsed;
      if (!compUi.current(token)) return;
      lastComp = c;
      compPieces = pieces;
      const pct = (1 - c.after.maxErrorUm / c.before.maxErrorUm) * 100;
      const base = fileName.replace(/\.[^.]*$/, '');
      compOut.replaceChildren(
        table(['', 'max error µm (vs original path)', 'motion time s'], [
          ['original', h('span', { id: 'toolpath-before-error' }, fmt(c.before.maxErrorUm, 4)), fmt(c.before.motionTime, 5)],
          ['compensated', h('span', { id: 'toolpath-after-error' }, fmt(c.after.maxErrorUm, 4)), h('span', { id: 'toolpath-after-time' }, fmt(c.after.motionTime, 5))],
        ]),
        h('p', {}, `Error ${pct >= 0 ? 'reduced' : 'increased'} by ${fmt(Math.abs(pct), 3)} %; rounds: ${c.historyUm.length ? `${c.historyUm.map((e) => fmt(e, 3)).join(' → ')} µm` : 'none (nothing to move)'}; dwells: ${c.dwells.length ? c.dwells.map((d) => `${d.seconds} s after line ${d.afterLine}`).join(', ') : 'none'}; corner spikes: ${c.spikes.length ? `${c.spikes.length} (${fmt(c.spikes.reduce((m, x) => Math.min(m, x.depthUm), Infinity), 3)}–${fmt(c.spikes.reduce((m, x) => Math.max(m, x.depthUm), 0), 3)} µm out and back, after lines ${c.spikes.slice(0, 5).map((x) => x.afterLine).join(', ')}${c.spikes.length > 5 ? ', …' : ''})` : 'none'}.`),
        ...(c.budgetNote ? [h('p', { class: 'note', id: 'toolpath-budget-note' }, `Cut short: ${c.budgetNote}.`)] : []),
        // The core says when the dwells' form is a guess (P in ms, no sign of the control in the program).
        ...(c.dwellNote ? [h('p', { class: 'warn-note', id: 'toolpath-dwell-note', role: 'note' }, `Check the dwells: ${c.dwellNote}.`)] : []),
        // The core says when it wrote the program flat (its largest error sat on computed moves), or why it could not.
        ...(c.expandNote ? [h('p', { class: c.expanded ? 'warn-note' : 'note', id: 'toolpath-expand-note', role: 'note' }, c.expanded ? `Written flat: ${c.expandNote}.` : `Not written flat: ${c.expandNote.replace(/^not written flat: /, '')}.`)] : []),
        // The core says when the written program is the original byte for byte: no download of a file that compensates nothing.
        ...(c.unchanged ? [h('p', { class: 'note', id: 'toolpath-unchanged' }, `No compensated program: ${c.unchanged}.`)] : []),
        h('button', { id: 'toolpath-download', class: 'primary', disabled: Boolean(c.unchanged), title: c.unchanged ?? '', onclick: () => downloadText(`${base}-compensated.nc`, c.nc, 'text/plain') }, c.unchanged ? 'Download compensated .nc (nothing changed)' : c.expanded ? 'Download compensated .nc (written flat)' : 'Download compensated .nc'),
        h('details', { id: 'toolpath-regions', open: c.regions.some((r) => !r.changed) },
          h('summary', {}, `${c.regions.filter((r) => r.changed).length} of ${c.regions.length} region(s) changed; the others are left unchanged, and why`),
          table(['lines', 'arcs / lines', 'before µm', 'after µm', 'changed', 'left unchanged because'], c.regions.slice(0, 500).map((r) => [
            `${r.firstLine}–${r.lastLine}`, `${r.arcs} / ${r.lines}`, fmt(r.beforeUm, 4), fmt(r.afterUm, 4), r.changed ? 'yes' : 'no', r.reason || '—',
          ])),
          c.regions.length > 500 ? h('p', {}, `(first 500 of ${c.regions.length} regions shown)`) : ''),
        h('div', { class: 'plot', id: 'toolpath-comp-path' }, h('div', { class: 'chart-title' }, 'Before and after in 3D (colour: contour error µm against the original path, one scale for both)'), compWhich, compView.el),
        h('details', {}, h('summary', {}, 'Compensated program'), h('pre', { id: 'toolpath-comp-nc', style: 'max-height:300px;overflow:auto' }, c.nc)),
      );
      await showComp();
      if (!compUi.current(token)) return;
      compUi.ok();
    } catch (e) {
      lastComp = null;
      if (compUi.current(token)) compRun.failed(abort, e, compUi, 'Reverse compensation');
    } finally {
      compRun.finish(abort);
    }
  }

  // Results shown are marked outdated as soon as a model input is edited
  // (a new program clears them: programChanged).
  const modelFields = [tA.el, tx.el, ty.el, tz.el, ovr.el, dt.el, radiiField];
  simUi.dependsOn(...modelFields);
  compUi.dependsOn(...modelFields, budget.el);
  run.addEventListener('click', simulate);
  comp.addEventListener('click', compensate);
  root.replaceChildren(
    h('div', { class: 'card' },
      h('h3', {}, 'NC program'),
      h('div', { class: 'row', style: 'display:flex;flex-wrap:wrap;gap:12px;align-items:flex-end' }, example.el, drop, radiiField),
      files.note,
      bigNote,
      h('div', { style: 'display:grid;grid-template-columns:repeat(auto-fit,minmax(280px,1fr));gap:12px' }, editor.el, check)),
    h('div', { class: 'card' },
      h('h3', {}, 'Model (Eq. 1 moving average tA, Eq. 2 first-order lag T per axis)'),
      h('div', { class: 'row', style: 'display:flex;flex-wrap:wrap;gap:12px;align-items:flex-end' }, tA.el, tx.el, ty.el, tz.el, ovr.el, dt.el),
      h('div', { class: 'row', style: 'display:flex;flex-wrap:wrap;gap:12px;align-items:flex-end' }, run, simCancel, budget.el, fromLine.el, toLine.el, comp, cancel, h('label', {}, 'Error magnification ', mag, ' ', magLabel))),
    h('div', { class: 'card' }, h('h3', {}, 'Simulation'), simProgress.el, out, pathBox, velBox),
    h('div', { class: 'card' }, h('h3', {}, 'Reverse compensation (§4-3)'), compProgress.el, compOut),
  );
  checkProgram();
}
