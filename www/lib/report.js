// "Download report": one self-contained HTML file of one tab or all tabs —
// date, software version, every card of the panel with its inputs (as
// values), its result tables (ISO 230-4, ISO 10791-6 blocks among them) and
// its plots and 3D views as PNG images (canvas.toDataURL) — with a print stylesheet for
// A4. Nothing is recomputed: the report is what the page shows.
import { h } from './ui.js';

const CSS = `
body { font: 10.5pt/1.4 system-ui, sans-serif; color: #1d2733; margin: 1.5rem auto; max-width: 190mm; }
h1 { font-size: 16pt; margin: 0 0 .2rem; } h2 { font-size: 13pt; border-bottom: 1px solid #c9d1da; margin: 1.4rem 0 .4rem; }
h3 { font-size: 11pt; margin: 1rem 0 .3rem; } h4 { font-size: 10pt; margin: .6rem 0 .2rem; }
.meta td { padding: .05rem .8rem .05rem 0; } .lead { color: #4a5562; }
table { border-collapse: collapse; margin: .3rem 0; font-size: 9pt; } th, td { border: 1px solid #d3dae2; padding: .15rem .4rem; text-align: left; vertical-align: top; }
.field { display: inline-block; margin: 0 1rem .2rem 0; } .field > span:first-child::after { content: ': '; }
.value { font-weight: 600; } figure { margin: .5rem 0; break-inside: avoid; } figure img { max-width: 100%; border: 1px solid #e3e8ee; }
figcaption { font-size: 9pt; color: #4a5562; } pre { font-size: 8pt; max-height: none; white-space: pre-wrap; }
.error-box { color: #b3261e; } .card { break-inside: avoid-page; } .unit { color: #4a5562; }
@page { size: A4; margin: 15mm; }
@media print { body { margin: 0; max-width: none; } h2 { break-before: auto; } a { color: inherit; } }
`;

/** True when `el` holds a result area (runState) with a result in it. */
const hasResult = (el) => [...el.querySelectorAll('[data-result]')].some((a) => a.childElementCount > 0);

/** The report section of one panel (a detached element), or null when
 * none of its results has been computed. */
function panelSection(panel) {
  if (!hasResult(panel)) return null;
  const section = h('section', { class: 'report-panel', id: `report-${panel.dataset.panel}` });
  section.append(h('h2', {}, panel.querySelector('h2')?.textContent || panel.dataset.panel));
  const lead = panel.querySelector('.lead');
  if (lead) section.append(h('p', { class: 'lead' }, lead.textContent));
  const body = panel.querySelector('.panel-body');
  const clone = body.cloneNode(true);
  // Plots → images with their titles and legends.
  const charts = [...body.querySelectorAll('.chart')];
  [...clone.querySelectorAll('.chart')].forEach((c, i) => {
    const orig = charts[i];
    const fig = h('figure', {});
    const title = orig.querySelector('.chart-title')?.textContent;
    for (const cv of orig.querySelectorAll('canvas')) {
      if (cv.width && cv.height && !cv.closest('.u-over')) fig.append(h('img', { src: cv.toDataURL('image/png'), alt: title || 'plot' }));
    }
    const legend = [...orig.querySelectorAll('.legend span, .u-legend .u-series .u-label')].map((x) => x.textContent.trim()).filter(Boolean);
    const axes = [...orig.querySelectorAll('.u-axis .u-label')].map((x) => x.textContent.trim()).filter(Boolean);
    fig.append(h('figcaption', {}, [title, axes.length ? `axes: ${axes.join(' / ')}` : '', legend.length ? `series: ${legend.join(', ')}` : ''].filter(Boolean).join(' — ')));
    c.replaceWith(fig);
  });
  // Form controls → their values.
  const controls = [...body.querySelectorAll('input, select, textarea')];
  [...clone.querySelectorAll('input, select, textarea')].forEach((c, i) => {
    const o = controls[i];
    let v;
    if (o.type === 'file' || o.type === 'range') v = null;
    else if (o.type === 'checkbox') v = o.checked ? 'yes' : 'no';
    else if (o.type === 'radio') v = o.checked ? '◉' : '○';
    else if (o.tagName === 'SELECT') v = o.selectedOptions[0]?.textContent ?? o.value;
    else v = o.value;
    if (v === null) c.remove();
    else if (o.tagName === 'TEXTAREA') c.replaceWith(h('pre', {}, v));
    else c.replaceWith(h('span', { class: 'value' }, v === '' ? '—' : v));
  });
  // 3D views (WebGL, lib/path3d.js) → an image of what each shows (after
  // the controls, which are matched to the page's by position), drawn
  // in this task (WebGL keeps no drawing buffer between frames), with its
  // legend as the caption.
  const views = [...body.querySelectorAll('.path3d')];
  [...clone.querySelectorAll('.path3d')].forEach((c, i) => {
    const orig = /** @type {any} */ (views[i]);
    const cv = orig.querySelector('canvas');
    const fig = h('figure', {});
    if (orig.pathView && cv?.width && cv.height) {
      orig.pathView.render();
      fig.append(h('img', { src: cv.toDataURL('image/png'), alt: 'tool path in 3D' }));
    }
    fig.append(h('figcaption', {}, orig.querySelector('.path3d-legend')?.textContent ?? ''));
    c.replaceWith(fig);
  });
  // Only the cards that were run: a card with result areas, all empty, is left out.
  [...body.querySelectorAll('.card')].forEach((c, i) => {
    if (c.querySelector('[data-result]') && !hasResult(c)) clone.querySelectorAll('.card')[i].dataset.notRun = '';
  });
  for (const c of clone.querySelectorAll('[data-not-run]')) c.remove();
  for (const d of clone.querySelectorAll('details')) d.open = true;
  for (const x of clone.querySelectorAll('button, .drop, .chart-hint, .progress, [hidden], script')) x.remove();
  for (const x of clone.querySelectorAll('[id]')) x.removeAttribute('id');
  section.append(...clone.childNodes);
  return section;
}

/** The report as one HTML string: `names` are the panels to include. */
export function reportHtml(names) {
  const version = /Core v([^\s]+)/.exec(document.getElementById('status')?.textContent || '')?.[1] || 'unknown';
  const now = new Date();
  const all = names.map((n) => document.getElementById(`panel-${n}`)).filter(Boolean);
  const sections = all.map((p) => [p, panelSection(p)]);
  const panels = sections.filter(([, s]) => s).map(([p]) => p);
  const notRun = sections.filter(([, s]) => !s).map(([p]) => p.querySelector('h2')?.textContent || p.dataset.panel);
  const field = (id) => /** @type {HTMLInputElement | null} */ (document.getElementById(id))?.value.trim() || '—';
  const doc = h('div', {},
    h('h1', {}, 'mtmotion report'),
    h('table', { class: 'meta', id: 'report-meta' }, h('tbody', {},
      h('tr', {}, h('td', {}, 'Date'), h('td', { id: 'report-date' }, now.toISOString().replace('T', ' ').replace(/\.\d+Z$/, ' UTC'))),
      h('tr', {}, h('td', {}, 'Software'), h('td', { id: 'report-version' }, `mtmotion core v${version} (WebAssembly, computed in the browser)`)),
      h('tr', {}, h('td', {}, 'Machine'), h('td', { id: 'report-machine-value' }, field('report-machine'))),
      h('tr', {}, h('td', {}, 'Operator'), h('td', { id: 'report-operator-value' }, field('report-operator'))),
      h('tr', {}, h('td', {}, 'Contents'), h('td', {}, panels.map((p) => p.querySelector('h2')?.textContent).join('; ') || 'nothing has been run yet')),
      ...(notRun.length ? [h('tr', {}, h('td', {}, 'Not run (left out)'), h('td', { id: 'report-not-run' }, notRun.join('; ')))] : []))),
    h('p', { class: 'unit' }, 'Every value below is as shown on the page when the report was made: inputs as entered, results as computed by the core. Plots are images.'),
    ...sections.map(([, s]) => s).filter(Boolean),
  );
  return `<!doctype html>\n<html lang="en"><head><meta charset="utf-8"><title>mtmotion report ${now.toISOString().slice(0, 10)}</title><meta name="viewport" content="width=device-width, initial-scale=1"><style>${CSS}</style></head><body>${doc.innerHTML}</body></html>\n`;
}
