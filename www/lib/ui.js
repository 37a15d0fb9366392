// Small DOM helpers shared by the panels. No model logic lives here.

/** Creates an element: h('div', { class: 'card', onclick: f }, child, …). */
export function h(tag, attrs = {}, ...children) {
  const el = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (v === undefined || v === null || v === false) continue;
    if (k === 'class') el.className = v;
    else if (k === 'style' && typeof v === 'string') el.style.cssText = v;
    else if (k === 'dataset') Object.assign(el.dataset, v);
    else if (k.startsWith('on') && typeof v === 'function') el.addEventListener(k.slice(2), v);
    else if (k in el && typeof v !== 'string') el[k] = v;
    else el.setAttribute(k, v === true ? '' : v);
  }
  for (const c of children.flat(Infinity)) {
    if (c === undefined || c === null || c === false) continue;
    el.append(c instanceof Node ? c : document.createTextNode(String(c)));
  }
  return el;
}

/**
 * A labelled number input. `value` reads the current number (NaN if empty).
 * @param {{ label: string, value: number | string, unit?: string, step?: number | string, min?: number,
 *   max?: number, id?: string, title?: string, onChange?: (value: number) => void }} options
 */
export function numberField({ label, value, unit, step = 'any', min, max, id, title, onChange }) {
  const input = h('input', { type: 'number', step, min, max, id, title, value: String(value) });
  // Blank by design (no default): a shared link may carry it blank.
  if (value === '') input.dataset.blank = 'ok';
  if (onChange) input.addEventListener('change', () => onChange(Number(input.value)));
  const el = h('label', { class: 'field', title }, h('span', {}, label, unit ? h('span', { class: 'unit' }, ` [${unit}]`) : null), input);
  return {
    el,
    input,
    get value() {
      return input.value === '' ? NaN : Number(input.value);
    },
    set value(v) {
      input.value = String(v);
    },
  };
}

/**
 * A labelled select; options are [value, text] pairs.
 * @param {{ label: string, options: string[][], value?: string, id?: string, onChange?: (value: string) => void }} options
 */
export function selectField({ label, options, value, id, onChange }) {
  const select = h('select', { id }, options.map(([v, t]) => h('option', { value: v, selected: v === value }, t)));
  if (onChange) select.addEventListener('change', () => onChange(select.value));
  const el = h('label', { class: 'field' }, h('span', {}, label), select);
  return {
    el,
    input: select,
    get value() {
      return select.value;
    },
    set value(v) {
      select.value = v;
    },
  };
}

/** A table from header strings and rows of cells (strings, numbers or nodes). */
export function table(headers, rows) {
  return h(
    'div',
    { class: 'table-wrap' },
    h('table', {}, h('thead', {}, h('tr', {}, headers.map((x) => h('th', {}, x)))), h('tbody', {}, rows.map((r) => h('tr', {}, r.map((c) => h('td', {}, c)))))),
  );
}

/** Offers `text` as a file download. */
export function downloadText(filename, text, mime = 'text/plain') {
  const url = URL.createObjectURL(new Blob([text], { type: `${mime};charset=utf-8` }));
  const a = h('a', { href: url, download: filename });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

/** CSV from named columns of equal length (shorter columns leave blanks). */
export function toCsv(columns) {
  const names = Object.keys(columns);
  const n = Math.max(0, ...names.map((k) => columns[k].length));
  const lines = [names.join(',')];
  for (let i = 0; i < n; i++) lines.push(names.map((k) => (i < columns[k].length ? String(columns[k][i]) : '')).join(','));
  return lines.join('\n') + '\n';
}

/** @type {(file: File) => Promise<unknown>} */
let fileCheck = async () => {};

/** Sets the check every drop zone runs on a file's size before reading it
 * (boot: the core's checkFileSize, through the worker). */
export function checkFilesWith(check) {
  fileCheck = check;
}

/**
 * Drag-and-drop area with a file picker; calls onText(text, fileName), or
 * with `multiple`, onFiles([{ text, name }, …]) once for all dropped files
 * (a file over `largeFrom` bytes as { file, name }, unread: the File, to
 * be read in chunks).
 * Each file's size is first checked by the core (checkFilesWith): a file
 * it would refuse is never read, and onRefused(error) shows the core's
 * budget error instead (reading 50 MB into the page stalls it), with the
 * dropped files' names.
 * A single-file zone with a `link` key (starting with its panel's name)
 * puts the dropped file in the shared link (linkedDrops).
 * With `onBytes`, a file that is not UTF-8 text (a .mat capture) goes
 * to onBytes(bytes, fileName) as a Uint8Array (the core reads it by its
 * format); a shared link cannot carry it.
 * @param {{ label?: string, accept?: string, id?: string, multiple?: boolean, link?: string, largeFrom?: number,
 *   onText?: (text: string, name: string) => unknown,
 *   onBytes?: (bytes: Uint8Array, name: string) => unknown,
 *   onFiles?: (files: { text?: string, file?: File, name: string }[]) => unknown,
 *   onRefused: (error: Error, names: string) => unknown }} options
 */
export function dropZone({ label = 'Drop a file here, or click to choose one', accept, onText, onBytes, multiple = false, onFiles, onRefused, id, link, largeFrom = Infinity }) {
  const input = h('input', { type: 'file', accept, hidden: true, multiple, id });
  const el = h('div', { class: 'drop', tabindex: 0, role: 'button' }, label, input);
  if (link && !multiple) linkedDrops.set(link, { el, onText, file: null });
  const read = async (files) => {
    const list = Array.from(files || []);
    if (!list.length) return;
    try {
      for (const f of list) await fileCheck(f);
    } catch (e) {
      return onRefused(e instanceof Error ? e : new Error(String(e)), list.map((f) => f.name).join(', '));
    }
    if (multiple) return onFiles(await Promise.all(list.map(async (f) => (f.size > largeFrom ? { file: f, name: f.name } : { text: await f.text(), name: f.name }))));
    /** @type {{ text: string, name: string, binary?: boolean }} */
    let file = { text: await list[0].text(), name: list[0].name };
    let bytes = null;
    if (onBytes) {
      const raw = new Uint8Array(await list[0].arrayBuffer());
      try {
        new TextDecoder('utf-8', { fatal: true }).decode(raw);
      } catch {
        bytes = raw;
        file = { text: '', name: list[0].name, binary: true };
      }
    }
    if (link) {
      linkedDrops.get(link).file = file;
      // The page's link follows every change; a dropped file is one.
      el.dispatchEvent(new Event('change', { bubbles: true }));
    }
    if (bytes && onBytes) return onBytes(bytes, file.name);
    return onText(file.text, file.name);
  };
  el.addEventListener('click', () => input.click());
  el.addEventListener('keydown', (e) => (e.key === 'Enter' || e.key === ' ') && input.click());
  input.addEventListener('change', () => read(input.files));
  el.addEventListener('dragover', (e) => {
    e.preventDefault();
    el.classList.add('over');
  });
  el.addEventListener('dragleave', () => el.classList.remove('over'));
  el.addEventListener('drop', (e) => {
    e.preventDefault();
    el.classList.remove('over');
    read(e.dataTransfer.files);
  });
  return el;
}

/**
 * Drop zones whose file travels in a shared link, by link key (the key
 * starts with the panel's name, e.g. 'ballbar-trace'): the zone, its
 * handler, and the file last dropped on it.
 * @type {Map<string, { el: HTMLElement, onText: (text: string, name: string) => unknown, file: { text: string, name: string, binary?: boolean } | null }>}
 */
export const linkedDrops = new Map();

/**
 * How long a run goes before its progress bar and the greying of the
 * previous results show. A result that comes sooner replaces the old one
 * with no flash of grey, and without the frames that the fade and the bar
 * cost while the workers compute (on 2 cores those frames took the cores
 * from the workers: docs/performance.md §5).
 */
export const SHOW_AFTER_MS = 200;

/** A progress bar: set(fraction 0…1, message), done(). It appears only
 * once a run has lasted SHOW_AFTER_MS, with the latest state. */
export function progressBar() {
  const bar = h('div');
  const msg = h('div', { class: 'progress-msg' });
  const el = h('div', { hidden: true }, h('div', { class: 'progress' }, bar), msg);
  let state = null;
  let timer = null;
  const render = () => {
    el.hidden = false;
    bar.style.width = `${Math.round(Math.max(0, Math.min(1, state[0])) * 100)}%`;
    msg.textContent = state[1];
  };
  return {
    el,
    set(fraction, message = '') {
      const first = state === null;
      state = [fraction, message];
      if (!el.hidden) render();
      else if (first)
        timer = setTimeout(() => {
          timer = null;
          if (state) render();
        }, SHOW_AFTER_MS);
    },
    done() {
      clearTimeout(timer);
      timer = null;
      state = null;
      el.hidden = true;
    },
  };
}

/**
 * One cancellable run at a time behind a Cancel `button` and a progress
 * `bar`: `start()` aborts the run before and returns the new run's
 * AbortController; `failed(c, e, ui, what)` ends the run state `ui` with
 * "`what` cancelled." when `c` was cancelled, else with the error `e`;
 * `finish(c)` hides the button and the bar if `c` is still the current run.
 */
export function cancelGuard(button, bar) {
  let current = null;
  button.addEventListener('click', () => current?.abort());
  return {
    start() {
      current?.abort();
      current = new AbortController();
      return current;
    },
    failed(c, e, ui, what) {
      ui.fail(c.signal.aborted ? new Error(`${what} cancelled.`) : e);
    },
    finish(c) {
      if (current !== c) return;
      current = null;
      button.hidden = true;
      bar.done();
    },
  };
}

/** Replaces the content of `container` with an error message. */
export function showError(container, err) {
  const box = h('div', { class: 'error-box', role: 'alert' }, String((err && err.message) || err));
  container.replaceChildren(box);
  return box;
}

/** Formats a number with `digits` significant-ish decimals; '—' for non-finite.
 * A magnitude below 1e-12 is numerical noise in every unit the page shows
 * (3.458e-320 was shown once): it reads 0. */
export function fmt(x, digits = 3) {
  if (typeof x !== 'number' || !Number.isFinite(x)) return '—';
  const a = Math.abs(x);
  if (a < 1e-12) return (0).toFixed(digits);
  if (a < 1e-3 || a >= 1e6) return x.toExponential(digits);
  return x.toFixed(digits);
}

/** One run state for a panel's result areas. dependsOn(...inputs) marks
 * shown results outdated (class `outdated`, a note, downloads off) as soon
 * as one of those inputs is edited. start() marks the previous
 * results stale (class `stale`, `aria-busy`), disables the buttons in them
 * (no download of stale results) and greys them (class `dimmed`) if the
 * run lasts SHOW_AFTER_MS; ok() shows the new ones; fail(err) empties every
 * area and puts the error in place of the results in the first one.
 * start() returns a token; current(token) says whether a later run has
 * started since. */
export function runState(main, ...extra) {
  const areas = [main, ...extra];
  // The report includes only cards whose result areas hold a result.
  for (const a of areas) a.dataset.result = '';
  let token = 0;
  let dim = null;
  const settle = () => {
    clearTimeout(dim);
    for (const a of areas) {
      a.classList.remove('stale', 'dimmed');
      a.removeAttribute('aria-busy');
    }
  };
  let outdatedNote = null;
  let editedDuringRun = false;
  const clearOutdated = () => {
    editedDuringRun = false;
    outdatedNote?.remove();
    outdatedNote = null;
    for (const a of areas) a.classList.remove('outdated');
  };
  // An input edited after a run: the results shown belong to the inputs
  // before the edit. They stay readable, marked at once, with their
  // downloads off, until the next run.
  const markOutdated = (e) => {
    const t = e.target;
    if (!(t instanceof Element) || t.closest('[data-display]') || areas.some((a) => a.contains(t))) return;
    // An edit while a run is in flight: its result will already be outdated.
    if (areas.some((a) => a.classList.contains('stale'))) {
      editedDuringRun = true;
      return;
    }
    outdated();
  };
  const outdated = () => {
    if (outdatedNote || areas.every((a) => !a.childElementCount)) return;
    for (const a of areas) {
      a.classList.add('outdated');
      for (const b of a.querySelectorAll('button')) b.disabled = true;
    }
    outdatedNote = h('p', { class: 'outdated-note', role: 'status' }, 'Inputs changed since these results were computed: they show the previous inputs. Run again to update them.');
    main.prepend(outdatedNote);
  };
  return {
    /** Marks the results outdated when an input inside `containers` changes
     * (not a display-only control, marked `data-display`). */
    dependsOn(...containers) {
      for (const c of containers) {
        c.addEventListener('input', markOutdated);
        c.addEventListener('change', markOutdated);
      }
    },
    start() {
      clearTimeout(dim);
      clearOutdated();
      for (const a of areas) {
        a.classList.add('stale');
        a.setAttribute('aria-busy', 'true');
        for (const b of a.querySelectorAll('button')) b.disabled = true;
      }
      dim = setTimeout(() => {
        for (const a of areas) if (a.classList.contains('stale')) a.classList.add('dimmed');
      }, SHOW_AFTER_MS);
      return ++token;
    },
    current: (t) => t === token,
    ok() {
      const edited = editedDuringRun;
      settle();
      if (edited) outdated();
    },
    // A clear or a failure is the panel's newest state: a run still in
    // flight (say, the analysis of the previous file) must not draw over it.
    clear() {
      token++;
      clearOutdated();
      for (const a of areas) a.replaceChildren();
      settle();
    },
    fail(err) {
      token++;
      clearOutdated();
      for (const a of areas) a.replaceChildren();
      settle();
      return showError(main, err);
    },
  };
}

/** A value at a stated display resolution: rounded to `res` (0.01 → two
 * decimals) and printed as 0 when its magnitude is below the resolution, so
 * numerical noise (3.9e-13 µm) never shows as a value. '—' for non-finite. */
export function fmtRes(x, res = 0.01) {
  if (typeof x !== 'number' || !Number.isFinite(x)) return '—';
  const decimals = Math.max(0, Math.ceil(-Math.log10(res) - 1e-9));
  if (Math.abs(x) < res) return (0).toFixed(decimals);
  return (Math.round(x / res) * res).toFixed(decimals);
}

/** A resolution or threshold at a display resolution: '< 0.01' when it is
 * finer than the display shows (never 5.64e-12), else as fmtRes. */
export function fmtLimit(x, res = 0.01) {
  if (typeof x !== 'number' || !Number.isFinite(x)) return '—';
  return Math.abs(x) < res ? `< ${res}` : fmtRes(x, res);
}

/** WAI-ARIA tabs keyboard pattern on a tablist: Left/Right move to the
 * previous/next tab (wrapping), Home/End to the first/last; the focused tab
 * is activated (`select(name)`); only the selected tab is in the Tab order. */
export function ariaTabs(list, select) {
  const tabs = () => [...list.querySelectorAll('[role="tab"]')];
  const sync = () => {
    for (const t of tabs()) t.tabIndex = t.getAttribute('aria-selected') === 'true' ? 0 : -1;
  };
  list.addEventListener('keydown', (e) => {
    const all = tabs();
    const i = all.indexOf(document.activeElement);
    if (i < 0) return;
    const j = { ArrowRight: (i + 1) % all.length, ArrowLeft: (i - 1 + all.length) % all.length, Home: 0, End: all.length - 1 }[e.key];
    if (j === undefined) return;
    e.preventDefault();
    all[j].focus();
    select(all[j].dataset.tab);
    sync();
  });
  document.addEventListener('mtmotion:tab', sync);
  sync();
}

/** Text → deflate-raw → base64url (for a link's hash); null without
 * CompressionStream. */
export async function packText(text) {
  if (typeof CompressionStream === 'undefined') return null;
  const stream = new Blob([text]).stream().pipeThrough(new CompressionStream('deflate-raw'));
  const bytes = new Uint8Array(await new Response(stream).arrayBuffer());
  let bin = '';
  for (let i = 0; i < bytes.length; i += 0x8000) bin += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(bin).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

/** Inverse of packText. */
export async function unpackText(packed) {
  const bin = atob(packed.replace(/-/g, '+').replace(/_/g, '/'));
  const bytes = Uint8Array.from(bin, (c) => c.charCodeAt(0));
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate-raw'));
  return new Response(stream).text();
}

/** Longest packed text a shared link carries (characters of base64url). */
export const LINK_TEXT_LIMIT = 16000;
