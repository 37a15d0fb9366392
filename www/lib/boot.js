// Page start-up shared by the served page (main.js) and the single-file page
// (standalone.js): start the core, mount the panels, restore the deep link,
// then mark the page ready for the tests.
import { showError, ariaTabs, downloadText, packText, unpackText, LINK_TEXT_LIMIT, linkedDrops, h, checkFilesWith } from './ui.js';
import { reportHtml } from './report.js';

export const PANELS = ['servo', 'toolpath', 'ballbar', 'kinematics'];

function selectTab(name) {
  if (!PANELS.includes(name)) return;
  for (const b of byData('[data-tab]')) b.setAttribute('aria-selected', String(b.dataset.tab === name));
  for (const s of byData('[data-panel]')) s.hidden = s.dataset.panel !== name;
  document.dispatchEvent(new CustomEvent('mtmotion:tab', { detail: name }));
}

/** The HTML elements matching `selector` (every `[data-…]` the page marks is one). */
const byData = (selector) => /** @type {NodeListOf<HTMLElement>} */ (document.querySelectorAll(selector));

const activeTab = () => byData('[data-tab][aria-selected="true"]')[0]?.dataset.tab || PANELS[0];

// Deep links: the hash holds the panel and the values of its id'd inputs and
// selects, e.g. #tab=toolpath&toolpath-ta=0.064. Pasted programs and dropped
// traces travel deflated when they fit (addTexts below).
/** @returns {(HTMLInputElement | HTMLSelectElement)[]} */
function inputsOf(panel) {
  const all = /** @type {NodeListOf<HTMLInputElement | HTMLSelectElement>} */ (document.querySelectorAll(`#panel-${panel} input[id], #panel-${panel} select[id]`));
  return [...all].filter((e) => e.type !== 'file' && e.type !== 'button');
}

function writeHash() {
  const tab = activeTab();
  const q = new URLSearchParams({ tab });
  for (const e of inputsOf(tab)) q.set(e.id, e instanceof HTMLInputElement && e.type === 'checkbox' ? String(e.checked) : e.value);
  history.replaceState(null, '', `#${q}`);
  addTexts(tab, q);
}

/** The field's label as the user sees it (for messages), else its id. */
function labelOf(e) {
  return e.closest('label')?.querySelector('span')?.textContent?.trim() || e.id;
}

/**
 * Why a link's value cannot go into input `e`, or null when it can: the
 * same rules the input itself enforces (a finite number inside min/max, one
 * of a select's options, true/false for a checkbox, at most 200 characters).
 */
export function linkValueProblem(e, raw) {
  if (raw.length > 200) return `${labelOf(e)}: the value is ${raw.length} characters long`;
  if (e.tagName === 'SELECT') {
    const options = [...e.options].map((o) => o.value);
    return options.includes(raw) ? null : `${labelOf(e)}: '${raw}' is not one of ${options.join(', ')}`;
  }
  if (e.type === 'checkbox') return raw === 'true' || raw === 'false' ? null : `${labelOf(e)}: expected true or false`;
  if (e.type === 'number') {
    // A field that starts blank (a required entry with no default, or
    // "blank: the core's default") travels blank.
    if (raw.trim() === '' && e.dataset.blank === 'ok') return null;
    const v = Number(raw);
    if (raw.trim() === '' || !Number.isFinite(v)) return `${labelOf(e)}: '${raw}' is not a number`;
    const lo = e.min === '' ? -Infinity : Number(e.min);
    const hi = e.max === '' ? Infinity : Number(e.max);
    if (v < lo || v > hi) return `${labelOf(e)}: ${raw} is outside ${e.min || '−∞'} … ${e.max || '∞'}`;
  }
  return null;
}

// A pasted program (a panel's id'd textarea) travels in the link, deflated
// and base64url-coded, when it fits (LINK_TEXT_LIMIT); otherwise the link
// says so and the page asks for the program to be loaded again.
/** Longest text worth compressing for a link (characters). */
const LINK_PACK_MAX = 2_000_000;
const textsOf = (tab) => /** @type {NodeListOf<HTMLTextAreaElement>} */ (document.querySelectorAll(`#panel-${tab} textarea[id]`));

async function addTexts(tab, q) {
  for (const t of textsOf(tab)) {
    // Megabytes never fit a link; do not compress them on every change.
    const packed = t.value && t.value.length <= LINK_PACK_MAX ? await packText(t.value) : null;
    if (packed && packed.length <= LINK_TEXT_LIMIT) q.set(`${t.id}.z`, packed);
    else if (t.value) q.set(`${t.id}.z`, 'too-large');
  }
  for (const [key, drop] of linkedDrops) {
    if (!key.startsWith(`${tab}-`) || !drop.file) continue;
    if (drop.file.binary) {
      q.set(`${key}.z`, `binary:${drop.file.name.slice(0, 80)}`);
      continue;
    }
    const packed = drop.file.text.length <= LINK_PACK_MAX ? await packText(`${drop.file.name}\n${drop.file.text}`) : null;
    q.set(`${key}.z`, packed && packed.length <= LINK_TEXT_LIMIT ? packed : `too-large:${drop.file.name.slice(0, 80)}`);
  }
  if (activeTab() === tab) history.replaceState(null, '', `#${q}`);
}

/** A dropped trace from the link is dropped again (its panel's own handler
 * reads it); one too large for a link, or damaged, is named in a note. */
async function restoreDrops(tab, q) {
  for (const [key, drop] of linkedDrops) {
    const packed = q.get(`${key}.z`);
    if (!key.startsWith(`${tab}-`) || !packed) continue;
    let note = null;
    if (packed.startsWith('too-large')) note = `The shared link could not carry the file ${packed.slice(10) || ''} (too large for a link): load it again.`;
    else if (packed.startsWith('binary:')) note = `The shared link cannot carry the binary file ${packed.slice(7)} (a .mat capture): load it again.`;
    else {
      try {
        const text = await unpackText(packed);
        const cut = text.indexOf('\n');
        drop.file = { name: text.slice(0, cut), text: text.slice(cut + 1) };
        await drop.onText(drop.file.text, drop.file.name);
      } catch {
        note = 'The file in the shared link is damaged: load it again.';
      }
    }
    drop.el.parentElement.querySelector('.link-note')?.remove();
    if (note) drop.el.before(h('p', { class: 'error-box link-note', role: 'alert' }, note));
  }
}

async function restoreTexts(tab, q) {
  for (const t of textsOf(tab)) {
    const packed = q.get(`${t.id}.z`);
    if (!packed) continue;
    let note = null;
    if (packed === 'too-large') note = 'The shared link could not carry this program (too large for a link): load the file again.';
    else {
      try {
        t.value = await unpackText(packed);
        t.dispatchEvent(new Event('input', { bubbles: true }));
      } catch {
        note = 'The program in the shared link is damaged: load the file again.';
      }
    }
    t.parentElement.querySelector('.link-note')?.remove();
    if (note) t.before(h('p', { class: 'error-box link-note', role: 'alert' }, note));
  }
}

async function restoreHash() {
  const q = new URLSearchParams(location.hash.slice(1));
  const tab = q.get('tab');
  if (!tab || !PANELS.includes(tab)) return;
  selectTab(tab);
  // Values are checked against the inputs' own ranges before anything is
  // set; a link with a bad value sets nothing and runs nothing.
  const problems = inputsOf(tab)
    .filter((e) => q.has(e.id))
    .map((e) => linkValueProblem(e, q.get(e.id)))
    .filter(Boolean);
  if (problems.length) {
    const status = document.getElementById('status');
    status.textContent = `This link was not applied: ${problems.join('; ')}. The panel keeps its defaults and nothing was run.`;
    status.classList.add('error');
    return;
  }
  for (const e of inputsOf(tab)) {
    if (!q.has(e.id)) continue;
    if (e instanceof HTMLInputElement && e.type === 'checkbox') e.checked = q.get(e.id) === 'true';
    else e.value = q.get(e.id);
    e.dispatchEvent(new Event('input', { bubbles: true }));
    e.dispatchEvent(new Event('change', { bubbles: true }));
  }
  // Texts after the inputs (an example menu's change would overwrite them).
  await restoreTexts(tab, q);
  await restoreDrops(tab, q);
  // A panel marks its main action with data-run; a shared link re-runs it.
  byData(`#panel-${tab} [data-run]`)[0]?.click();
}

/** makeApi() → Promise<api>; loadPanel(name) → Promise<{ mount(root, api) }>. */
export async function boot({ makeApi, loadPanel }) {
  const status = document.getElementById('status');
  // Each tab change is a history entry (Back returns to the previous tab).
  const openTab = (name) => {
    if (name === activeTab()) return;
    selectTab(name);
    history.pushState(null, '', `#${new URLSearchParams({ tab: name })}`);
    writeHash();
  };
  for (const b of byData('[data-tab]')) b.addEventListener('click', () => openTab(b.dataset.tab));
  ariaTabs(document.querySelector('[role="tablist"]'), openTab);
  let api;
  try {
    api = await makeApi();
    // Proves the round trip with a real core call.
    const preset = await api.call('machinePreset', ['nmv5000']);
    status.textContent = `Core v${api.version} ready (${api.mode}) · default machine: ${preset.name}`;
    // The core decides whether a dropped file is small enough to read.
    checkFilesWith((file) => api.call('checkFileSize', [file.name, file.size]));
    // For the browser console and the browser test.
    globalThis.mtmotion = { api };
  } catch (e) {
    status.textContent = `The calculation core could not start: ${e.message}`;
    status.classList.add('error');
    console.error(e);
    return;
  }
  await Promise.all(
    PANELS.map(async (name) => {
      const body = document.querySelector(`#panel-${name} .panel-body`);
      try {
        const panel = await loadPanel(name);
        await panel.mount(body, api);
      } catch (e) {
        showError(body, e);
        console.error(`panel ${name}:`, e);
      }
    }),
  );
  // One self-contained HTML report of this tab or of all tabs.
  const report = (names) => downloadText(`mtmotion-report-${names.length > 1 ? 'all' : names[0]}-${new Date().toISOString().slice(0, 10)}.html`, reportHtml(names), 'text/html');
  document.getElementById('report-tab')?.addEventListener('click', () => report([activeTab()]));
  document.getElementById('report-all')?.addEventListener('click', () => report(PANELS));
  await restoreHash();
  document.querySelector('main').addEventListener('change', writeHash);
  window.addEventListener('hashchange', restoreHash);
  document.body.dataset.ready = 'true';
}
