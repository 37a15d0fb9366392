// Where and why, linked both ways (issue 28 item 3), on the built-in
// example: the worst cutting-move segments are listed (rapids apart) and
// marked in the 3D view; clicking the worst spot's mark, or its entry in
// the list, scrolls the editor to its line and selects it; putting the
// cursor on a line in the editor highlights its segment in the view (the
// highlight colour is drawn); clicking the path selects its line; hover
// shows line, time, error and feed; a mouse drag orbits the camera; keys
// zoom, pan and reset.
const HIGHLIGHT = 0xd6336c;

/** The editor's selected line (1-based) and whether it is inside the
 * scroller's visible box (waits up to 2 s for the editor to draw it). */
const editorLine = async (page) => {
  await page.waitForFunction(() => {
    const a = document.querySelector('.nc-editor .cm-activeLine')?.getBoundingClientRect();
    const box = document.querySelector('.nc-editor .cm-scroller').getBoundingClientRect();
    return a && a.top >= box.top - 1 && a.bottom <= box.bottom + 1;
  }, null, { timeout: 2_000 }).catch(() => {});
  return editorLineNow(page);
};
const editorLineNow = (page) => page.evaluate(() => {
  const t = /** @type {HTMLTextAreaElement} */ (document.querySelector('#toolpath-nc'));
  const line = t.value.slice(0, t.selectionStart).split('\n').length;
  const sel = t.value.slice(t.selectionStart, t.selectionEnd);
  const active = document.querySelector('.nc-editor .cm-activeLine');
  const box = document.querySelector('.nc-editor .cm-scroller').getBoundingClientRect();
  const r = active?.getBoundingClientRect();
  const visible = Boolean(r && r.top >= box.top - 1 && r.bottom <= box.bottom + 1);
  return { line, sel, text: t.value.split('\n')[line - 1], visible, activeText: active?.textContent ?? null };
});

const view = (page, fn, arg) => page.evaluate(([f, a]) => {
  const v = /** @type {any} */ (document.querySelector('#toolpath-path3d')).pathView;
  return new Function('v', 'a', `return (${f})(v, a);`)(v, a);
}, [fn.toString(), arg]);

export default async function (page, check) {
  await page.click('[data-tab="toolpath"]');
  await page.click('#toolpath-run');
  await page.waitForSelector('#toolpath-path3d .path3d-mark[data-rank="1"]', { timeout: 60_000 });
  await page.waitForFunction(() => document.querySelector('#toolpath-path3d').pathView.state().frames > 0);
  const headline = parseFloat(await page.textContent('#toolpath-max-error'));
  const first = await page.$eval('#toolpath-worst tbody tr', (tr) => [...tr.children].map((c) => c.textContent));
  check(Math.abs(parseFloat(first[5]) - headline) <= 1e-3 * headline, `the worst-segments list starts at the headline maximum (${headline} µm), not above it: first row ${first.join(' | ')}`);
  check((await page.$$eval('#toolpath-worst a[data-kind="rapid"]', (as) => as.filter((a) => !a.closest('#toolpath-worst-rapids')).length)) === 0, 'no rapid in the cutting-move list');
  const marks = await page.$$eval('.path3d-mark', (bs) => bs.map((b) => Number(b.dataset.line)));
  const listed = await page.$$eval('#toolpath-worst a[data-kind="cutting"]', (as) => as.map((a) => Number(a.dataset.line)));
  check(marks.length === listed.length && marks.every((l, i) => l === listed[i]), `each listed segment has its mark in the view: marks ${marks}, list ${listed}`);

  // Clicking the worst spot's mark scrolls the editor to its line and selects it.
  await page.$eval('.nc-editor .cm-scroller', (s) => { s.scrollTop = 0; });
  const worstLine = marks[0];
  await page.click('.path3d-mark[data-rank="1"]');
  let ed = await editorLine(page);
  check(ed.line === worstLine && ed.sel === ed.text && ed.visible, `clicking mark #1 should select line ${worstLine} in view in the editor: ${JSON.stringify(ed)}`);
  // The same from the list (rank 10: another part of the program).
  await page.$eval('.nc-editor .cm-scroller', (s) => { s.scrollTop = 0; });
  const tenth = listed[listed.length - 1];
  await page.click(`#toolpath-worst a[data-rank="${listed.length}"][data-kind="cutting"]`);
  ed = await editorLine(page);
  check(ed.line === tenth && ed.visible, `clicking the list's line ${tenth} should select it in view in the editor: ${JSON.stringify(ed)}`);

  // A line clicked in the editor highlights its segment in the view.
  await view(page, (v) => v.highlightLine(0));
  const none = await view(page, (v, c) => v.countPixels(c), HIGHLIGHT);
  check(none < 5, `no highlight drawn before a line is clicked (${none} pixels of its colour)`);
  const target = marks[1];
  const at = await page.evaluate((n) => {
    const g = [...document.querySelectorAll('.nc-editor .cm-lineNumbers .cm-gutterElement')].find((e) => e.textContent === String(n));
    const r = g?.getBoundingClientRect();
    const c = document.querySelector('.nc-editor .cm-content').getBoundingClientRect();
    return r ? [c.left + 60, r.top + r.height / 2] : null;
  }, target);
  check(at !== null, `line ${target} should be on screen in the editor after the list click`);
  if (at) await page.mouse.click(at[0], at[1]);
  await page.waitForTimeout(100);
  const hl = await page.$eval('#toolpath-path3d', (e) => Number(e.dataset.highlightLine));
  const drawn = await view(page, (v, c) => v.countPixels(c), HIGHLIGHT);
  check(hl === target && drawn > none + 20, `clicking line ${target} in the editor should highlight its segment: highlighted line ${hl}, ${drawn} highlight pixels drawn`);

  // Clicking the path selects its line; hover tells line, time, error, feed.
  const canvas = await page.$('#toolpath-path3d canvas');
  await canvas.scrollIntoViewIfNeeded();
  const p = await view(page, (v, n) => v.screenOfLine(n), listed[2]);
  await page.mouse.move(p[0] + 1, p[1] + 1);
  await page.waitForSelector('.path3d-tip:not([hidden])', { timeout: 5_000 });
  const tip = await page.textContent('.path3d-tip');
  check(new RegExp(`line ${listed[2]} \\(F \\d+ mm/min\\)`).test(tip) && /t \d+\.\d+ s/.test(tip) && /error \d+\.\d+ µm/.test(tip) && /speed \d+ mm\/min/.test(tip), `hover should show line ${listed[2]}, feed, time, error and speed: "${tip}"`);
  await page.mouse.click(p[0], p[1]);
  ed = await editorLine(page);
  const picked = await page.$eval('#toolpath-path3d', (e) => Number(e.dataset.pickedLine));
  check(picked === listed[2] && ed.line === listed[2], `clicking the path on line ${listed[2]} should select it: picked ${picked}, editor at ${ed.line}`);

  // A drag orbits the camera (OrbitControls); the pick above left the page where it was.
  const b = await canvas.boundingBox();
  check(b.y >= 0 && b.y + b.height <= (page.viewportSize()?.height ?? 0) + 1, `a click in the view keeps it on screen (canvas at y ${b.y})`);
  const before = await view(page, (v) => v.camera.position.toArray());
  await page.mouse.move(b.x + b.width / 2, b.y + b.height / 2);
  await page.mouse.down();
  await page.mouse.move(b.x + b.width / 2 + 120, b.y + b.height / 2 + 40, { steps: 6 });
  await page.mouse.up();
  const after = await view(page, (v) => v.camera.position.toArray());
  check(before.some((x, i) => Math.abs(x - after[i]) > 1e-6), `a drag should orbit the camera: ${before} → ${after}`);

  // Keys on the focused view: + zooms, an arrow pans, 0 resets.
  await page.focus('#toolpath-path3d canvas');
  await page.keyboard.press('0');
  const rest = await view(page, (v) => [v.camera.zoom, ...v.controls.target.toArray()]);
  await page.keyboard.press('+');
  const zoomed = await view(page, (v) => v.camera.zoom);
  await page.keyboard.press('ArrowLeft');
  const panned = await view(page, (v) => v.controls.target.toArray());
  await page.keyboard.press('0');
  const reset = await view(page, (v) => [v.camera.zoom, ...v.controls.target.toArray()]);
  check(zoomed > rest[0] && panned.some((x, i) => Math.abs(x - rest[i + 1]) > 1e-9) && reset.every((x, i) => Math.abs(x - rest[i]) < 1e-9), `keys: + zooms (${rest[0]} → ${zoomed}), ArrowLeft pans (${panned}), 0 resets (${reset})`);
}
