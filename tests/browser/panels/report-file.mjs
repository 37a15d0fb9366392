import { readFileSync } from 'node:fs';
/** A report of a loaded ball-bar file names the file and leaves out the
 * synthetic generator's fields (it listed "Centre offset Y 10 µm" for a
 * file). */
export default async function (page, check) {
  await page.click('[data-tab="ballbar"]');
  const text = ['angle_deg,deviation_um', ...Array.from({ length: 361 }, (_, i) => `${i},${(2 * Math.cos((3 * i * Math.PI) / 180)).toFixed(4)}`)].join('\n');
  await page.setInputFiles('#panel-ballbar .drop input[type=file]:not([multiple])', { name: 'shop-floor-run.csv', mimeType: 'text/csv', buffer: Buffer.from(text) });
  await page.waitForFunction(() => /shop-floor-run\.csv: 1 run/.test(document.querySelector('#ballbar-file-info').textContent));
  await page.waitForSelector('#ballbar-results:not(.stale) #ballbar-iso');
  check(await page.isHidden('#ballbar-offset-y'), 'the synthetic centre offset field is hidden while a file is the trace');
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#report-tab')]);
  const html = readFileSync(await dl.path(), 'utf8');
  check(html.includes('shop-floor-run.csv'), 'the report names the loaded file');
  check(!/Centre offset Y/.test(html) && !/Servo mismatch \(X lags\)/.test(html), 'the report must not list the synthetic generator\'s fields for a loaded file');
}
