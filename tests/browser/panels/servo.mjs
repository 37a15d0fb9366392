// Servo panel: run the paper's test at ω = π with Best K_FFP and check the
// shown numbers against independent values: α_th of C is ω·Ts/2 with
// K_FFP = 100 % and integral action (Eq. 17: π·0.032 rad = 100.531 mrad), the
// mean α − β before is positive and of the order ω·(Ts_C − Ts_X)/4, and after
// Best K_FFP it is below 0.1 mrad.
export default async function (page, check) {
  await page.click('[data-tab="servo"]');
  await page.waitForSelector('#servo-best');
  await page.fill('#servo-omega', String(Math.PI));
  await page.click('#servo-best');
  await page.waitForSelector('#servo-alpha-th', { timeout: 60_000 });
  const alpha = Number(await page.textContent('#servo-alpha-th'));
  check(Math.abs(alpha - Math.PI * 32) < 0.01, `α_th should be π·32 mrad = 100.531, shown ${alpha}`);
  const before = Number(await page.textContent('#servo-mean-angle-diff'));
  const rough = (Math.PI * (0.064 - 0.05)) / 4 * 1e3; // X leads by (Ts_C − Ts_X)/2, averaged with Y
  check(before > 0.5 * rough && before < 2 * rough, `mean α − β before should be ≈ ${rough.toFixed(2)} mrad, shown ${before}`);
  const after = Number(await page.textContent('#servo-after-angle-diff'));
  check(Math.abs(after) < 0.1, `mean α − β after Best K_FFP should be < 0.1 mrad, shown ${after}`);
  const kx = Number(await page.textContent('#servo-kffp-x'));
  check(kx > 0 && kx < 100, `Best K_FFP of X should be lowered below 100 %, shown ${kx}`);
  check((await page.$$('#panel-servo .chart')).length >= 5, 'the panel should draw its charts');
  await traceCheck(page, check);
}

// Trace import: a synthetic SERVO GUIDE-style trace (ms, mm, degrees) in
// which X and Y follow the circle exactly and C lags by 2 mrad: Eq. 10 gives
// α − β = +2 mrad, independent of any servo model.
export async function traceCheck(page, check) {
  const omega = Math.PI;
  const lines = ['time,X,Y,C'];
  for (let i = 0; i <= 3000; i++) {
    const t = i * 1e-3;
    const th = t < 0.064 ? (omega * t * t) / (2 * 0.064) : omega * (t - 0.032);
    lines.push(`${i},${8 * Math.cos(th)},${8 * Math.sin(th)},${((th - 0.002) * 180) / Math.PI}`);
  }
  await page.setInputFiles('#panel-servo .drop input[type=file]', { name: 'trace.csv', mimeType: 'text/csv', buffer: Buffer.from(lines.join('\n')) });
  await page.waitForSelector('#servo-map-time');
  await page.selectOption('#servo-map-tunit', '0.001');
  await page.click('#servo-trace-run');
  await page.waitForSelector('#servo-trace-angle-diff', { timeout: 30_000 });
  const d = Number(await page.textContent('#servo-trace-angle-diff'));
  check(Math.abs(d - 2) < 1e-3, `the trace's mean α − β should be 2 mrad, shown ${d}`);
}
