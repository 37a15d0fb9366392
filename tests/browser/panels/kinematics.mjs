// Kinematics panel: an ideal machine with ideal servos reads 0 µm on the
// cone-frustum test (analytic: no error, no deviation), and compensating the
// S-shape program on a Monte-Carlo Pocket NC cuts the error std by ≥ 80 %
// (thasana: 80.73 %).
export default async function (page, check) {
  await page.click('[data-tab="kinematics"]');
  await page.waitForSelector('#kinematics-err-EX0C');
  await page.check('#kinematics-ideal');
  await page.click('#kinematics-cone-run');
  await page.waitForSelector('#kinematics-cone-max', { timeout: 120_000 });
  const max = parseFloat(await page.textContent('#kinematics-cone-max'));
  check(Number.isFinite(max) && Math.abs(max) < 1e-3, `ideal machine should read 0 µm, shows ${max} µm`);
  const rows = await page.$$eval('#kinematics-cone-table tbody tr', (r) => r.length);
  check(rows === 4, `four runs (15°/45° × perpendicular/parallel) expected, got ${rows}`);
  await page.selectOption('#kinematics-machine', 'pocketnc-v2-10');
  await page.waitForFunction(() => document.querySelector('#kinematics-nc-input').value.includes('G1'));
  await page.click('#kinematics-nc-run');
  await page.waitForSelector('#kinematics-nc-reduction', { timeout: 120_000 });
  const red = parseFloat(await page.textContent('#kinematics-nc-reduction'));
  check(red >= 80, `compensation should cut the std by ≥ 80 %, shows ${red} %`);
}
