// Servo panel: the J+J1 labels follow the C axis' J as the user edits it
// (they were once hard-coded to the paper's 4.2 kg·m²). Editing J to 5.0
// must relabel the J1 options to 5.0 + J1, and the paper's sweep table and
// saturation table must show the core's J + J1 for the edited J, labelled
// as the user's axis; the sweep runs on the user's own loads and speeds.
export default async function (page, check) {
  await page.click('[data-tab="servo"]');
  await page.waitForSelector('#servo-p-c-j');
  await page.fill('#servo-p-c-j', '5');
  const labels = await page.$$eval('#servo-j1 option', (os) => os.map((o) => o.textContent));
  const want = [1.7, 3.24, 4.77].map((v) => (5 + v).toFixed(2));
  for (const [i, w] of want.entries()) {
    check(labels[i]?.includes(`J+J1 = ${w}`), `J1 option ${i} should read J+J1 = ${w} after J = 5, shows "${labels[i]}"`);
  }
  await page.click('#servo-sweep');
  await page.waitForSelector('#servo-saturation-table', { timeout: 120_000 });
  const satJ = await page.$$eval('#servo-saturation-table tbody tr td:first-child', (tds) => tds.map((t) => t.textContent));
  check(JSON.stringify(satJ) === JSON.stringify(want), `saturation table J+J1 should be ${want}, shows ${satJ}`);
  const sweepJ = await page.$$eval('#servo-sweep-table tbody tr td:first-child', (tds) => [...new Set(tds.map((t) => t.textContent))]);
  check(JSON.stringify(sweepJ) === JSON.stringify(want), `sweep table J+J1 should be ${want}, shows ${sweepJ}`);
  // An edited axis is the user's: the paper's quoted points are not shown beside ours.
  const head = await page.textContent('#servo-saturation-table thead');
  check(!/paper/.test(head) && /your axis/.test(head), `an edited table's saturation header should say "your axis", not "paper / ours": "${head}"`);
  check(/as edited/.test(await page.textContent('#servo-sweep-whose')), 'the note should say the axis is the table as edited');
  // The user's own loads and speeds.
  await page.fill('#servo-sweep-j1', '2.5');
  await page.fill('#servo-sweep-omega', '2, 1');
  await page.click('#servo-sweep');
  await page.waitForSelector('#servo-sweep-results:not(.stale) #servo-saturation-table', { timeout: 120_000 });
  const own = await page.$$eval('#servo-saturation-table tbody tr td:first-child', (tds) => tds.map((t) => t.textContent));
  check(JSON.stringify(own) === JSON.stringify(['7.50']), `one load J1 = 2.5 on J = 5 should give J+J1 = 7.50, shows ${own}`);
  const rows = await page.$$eval('#servo-sweep-table tbody tr', (trs) => trs.map((t) => t.children[1].textContent));
  check(JSON.stringify(rows) === JSON.stringify(['0.6π', '0.3π']), `the sweep should run at ω = 2 and 1 rad/s, rows ${rows}`);
  await page.fill('#servo-sweep-j1', '2.5, heavy');
  await page.click('#servo-sweep');
  await page.waitForSelector('#servo-sweep-results .error-box');
  const err = await page.textContent('#servo-sweep-results .error-box');
  check(/Sweep loads J1 \[kg·m²\]: 'heavy' is not a number/.test(err), `a bad load should be named, says "${err}"`);
}
