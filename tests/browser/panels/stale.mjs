// One run state per panel: after a successful run, a failing run must show
// its error in place of the results — no chart, table or enabled download
// of the previous run stays on screen — and the "loaded file" line must
// name the file that failed, not the previous one. Errors name fields by
// their page label and unit.

export default async function (page, check) {
  // ---- servo: a good simulation, then a bad R_C.
  await page.click('[data-tab="servo"]');
  await page.click('#servo-run');
  await page.waitForSelector('#servo-mean-angle-diff');
  await page.waitForFunction(() => document.querySelectorAll('#servo-charts .uplot').length > 0);
  await page.fill('#servo-rc', '-5');
  await page.click('#servo-run');
  await page.waitForSelector('#servo-results .error-box');
  check(!(await page.$('#servo-mean-angle-diff')), 'servo: the previous mean α − β must be gone after a failed run');
  check((await page.$$('#servo-charts .uplot, #servo-charts canvas')).length === 0, 'servo: the previous charts must be gone after a failed run');
  check(await page.isDisabled('#servo-csv'), 'servo: the CSV download must not offer the previous run');
  // The error names the field as the page labels it, not by its code name.
  const msg = await page.textContent('#servo-results .error-box');
  check(msg.includes('R_C [mm] = -5') && !/condition `rc`/.test(msg), `servo: the error should name R_C [mm], says "${msg}"`);

  // An emptied axis-table cell is named by its row, axis and unit, not by its API key.
  await page.fill('#servo-rc', '5');
  await page.fill('#servo-p-c-kpp', '');
  await page.click('#servo-run');
  await page.waitForSelector('#servo-results .error-box');
  const empty = await page.textContent('#servo-results .error-box');
  check(/C axis, Kpp \[1\/s\]: empty/.test(empty) && !/missing key|machine\.axes/.test(empty), `servo: an empty Kpp should be named "C axis, Kpp [1/s]", says "${empty}"`);
  await page.fill('#servo-p-c-kpp', '-3');
  await page.click('#servo-run');
  await page.waitForFunction(() => /= -3/.test(document.querySelector('#servo-results .error-box')?.textContent ?? ''));
  const neg = await page.textContent('#servo-results .error-box');
  check(/C axis, Kpp \[1\/s\] = -3/.test(neg) && !/axis parameter `kpp`/.test(neg), `servo: a bad Kpp should be named by its label, says "${neg}"`);

  // ---- tool path: a good simulation, then a program with an error.
  await page.click('[data-tab="toolpath"]');
  await page.click('#toolpath-run');
  await page.waitForSelector('#toolpath-max-error');
  await page.fill('#toolpath-nc', 'G90 G01 X10 Y0 F1000\nG01 X=5\n');
  await page.click('#toolpath-run');
  await page.waitForSelector('#toolpath-out .error-box');
  check(!(await page.$('#toolpath-max-error')), 'tool path: the previous maximum error must be gone');
  check((await page.$$('#toolpath-path canvas, #toolpath-path svg, #toolpath-velocity .uplot')).length === 0, 'tool path: the previous path and velocity plots must be gone');

  // ---- ball bar: a good file, then a file that is not a trace.
  await page.click('[data-tab="ballbar"]');
  const good = ['angle_deg,deviation_um', ...Array.from({ length: 361 }, (_, i) => `${i},${(3 * Math.sin((2 * i * Math.PI) / 180)).toFixed(4)}`)].join('\n');
  const input = await page.$('#panel-ballbar .drop input[type=file]:not([multiple])');
  await input.setInputFiles({ name: 'good.csv', mimeType: 'text/csv', buffer: Buffer.from(good) });
  await page.waitForFunction(() => /good\.csv: 1 run/.test(document.querySelector('#ballbar-file-info').textContent));
  await page.waitForSelector('#ballbar-centre-x');
  await input.setInputFiles({ name: 'bad.csv', mimeType: 'text/csv', buffer: Buffer.from('foo,bar\n1,2\n3,4\n') });
  await page.waitForSelector('#ballbar-results .error-box');
  const info = await page.textContent('#ballbar-file-info');
  check(!info.includes('good.csv') && info.includes('bad.csv'), `ball bar: the loaded-file line should name bad.csv, not good.csv: "${info}"`);
  check(!(await page.$('#ballbar-centre-x')), 'ball bar: the previous fitted centre must be gone');
}
