// Ball bar & alignment panel: a synthetic trace with a known centre offset and
// backlash is analysed in the page; the shown fitted centre and the ISO 230-4
// diagnostics must return the values put in, and the paper's Fig. 7 example
// must show an unbiased centre at 360°.
export default async function (page, check) {
  await page.click('[data-tab="ballbar"]');
  await page.waitForSelector('#ballbar-iso');
  // Full circle, centre (15, −8) µm, backlash X 4 µm, no motion harmonics.
  await page.fill('#ballbar-range', '360');
  await page.fill('#ballbar-offset-x', '15');
  await page.fill('#ballbar-offset-y', '-8');
  await page.fill('#ballbar-backlash-x', '4');
  await page.fill('#ballbar-harmonics-input', '3:2');
  await page.click('#ballbar-run');
  await page.waitForFunction(() => document.querySelector('#ballbar-centre-x')?.textContent && !document.querySelector('#ballbar-results').classList.contains('stale'));
  const cx = Number(await page.textContent('#ballbar-centre-x'));
  const cy = Number(await page.textContent('#ballbar-centre-y'));
  // Neither the backlash signature sign(sin θ)·cos θ nor the trefoil has a
  // first harmonic, so the least-squares centre is the offset put in.
  check(Math.abs(cx - 15) < 0.05 && Math.abs(cy + 8) < 0.05, `fitted centre should be near (15, −8) µm, shows (${cx}, ${cy})`);
  const diag = await page.textContent('#ballbar-diagnostics');
  const m = /Backlash X\s*([-\d.]+) µm/.exec(diag);
  check(m && Math.abs(Number(m[1]) - 4) < 0.1, `backlash X should read 4 µm, table says: ${m && m[1]}`);
  const iso = await page.textContent('#ballbar-iso');
  check(/CCW/.test(iso) && /CW/.test(iso), 'the ISO 230-4 table should have CCW and CW rows');
  // Trefoil 2 µm: G ≥ 4 µm per direction (plus the backlash steps).
  const g = Number((await page.$$eval('#ballbar-iso tbody tr td:nth-child(2)', (tds) => tds.map((t) => t.textContent)))[0]);
  check(g >= 4 && g < 9, `G of the CCW run should be about 4–8 µm, shows ${g}`);
  check(await page.isVisible('#ballbar-sweep'), 'the travel-range sweep should be drawn');
  // The paper's Fig. 7 example: at 360° the estimate is unbiased.
  await page.click('#ballbar-example-run');
  await page.waitForSelector('#ballbar-paper-table');
  const rows = await page.$$eval('#ballbar-paper-table tbody tr', (trs) => trs.map((tr) => Array.from(tr.children, (td) => td.textContent)));
  const r360 = rows.find((r) => r[1] === '360');
  check(r360 && Math.abs(Number(r360[3])) < 0.01, `Fig. 7 at 360° should show ≈ 0 µm, row: ${JSON.stringify(r360)}`);
}
