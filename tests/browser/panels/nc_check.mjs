// Tool-path panel, program check : a program with two errors
// lists both next to the text, each naming its line; clicking one selects
// that line in the text. A valid program shows the summary (here one
// 10 mm line at F600 → 1 s) and its warnings grouped by kind.
export default async function (page, check) {
  await page.click('[data-tab="toolpath"]');
  await page.waitForSelector('#toolpath-nc');
  await page.fill('#toolpath-nc', 'G21\nG1 X1\nG0 X2\nG1 Y(open');
  await page.waitForSelector('#toolpath-check-errors li', { timeout: 30_000 });
  const lines = await page.$$eval('#toolpath-check-errors a.nc-line', (as) => as.map((a) => Number(a.dataset.line)));
  check(JSON.stringify(lines) === '[2,4]', `errors listed at lines ${lines}`);
  await page.click('#toolpath-check-errors li:nth-child(2) a');
  const sel = await page.$eval('#toolpath-nc', (t) => t.value.slice(t.selectionStart, t.selectionEnd));
  check(sel === 'G1 Y(open', `clicking the error selects its line: '${sel}'`);

  await page.fill('#toolpath-nc', 'G21 G55\nG1 X10 F600');
  await page.waitForSelector('#toolpath-check-warnings', { timeout: 30_000 });
  const text = await page.textContent('#toolpath-check');
  const t = parseFloat(await page.textContent('#toolpath-check-time'));
  check(Math.abs(t - 1) < 1e-9, `summary shows ${t} s for 10 mm at 600 mm/min`);
  check(text.includes('work offset (1)'), 'warnings grouped by kind');
}
