// Servo panel: the J+J1 labels follow the C axis' J as the user edits it
// (they were once hard-coded to the paper's 4.2 kg·m²). Editing J to 5.0
// must relabel the J1 options to 5.0 + J1, and the paper's sweep table and
// saturation table must show the core's J + J1 for the edited J.
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
}
