// Report: after a ball-bar analysis and a cone-frustum run, "Report (all
// tabs)" downloads one HTML file that opens with the network cut off and
// loads nothing (every plot an inlined PNG), with the date, the software
// version, all four tabs, the inputs as values, the ISO 230-4 and
// ISO 10791-6 result blocks, and an A4 print stylesheet; machine and
// operator, a G tolerance verdict, and only the tabs and cards that were run.
import { readFileSync } from 'node:fs';

export default async function (page, check) {
  await page.click('[data-tab="ballbar"]');
  await page.waitForSelector('#ballbar-results:not(.stale) #ballbar-iso');
  await page.click('[data-tab="kinematics"]');
  await page.waitForSelector('#kinematics-err-EX0C');
  await page.check('#kinematics-ideal');
  await page.click('#kinematics-cone-run');
  await page.waitForSelector('#kinematics-cone-out:not(.stale) #kinematics-cone-max', { timeout: 120_000 });
  await page.fill('#report-machine', 'VMC-7 #1042');
  await page.fill('#report-operator', 'A. Ito');
  // A G tolerance gives a pass/fail column (G of the default trace is a few µm: 1 µm fails, 100 passes).
  await page.click('[data-tab="ballbar"]');
  await page.fill('#ballbar-tolerance', '1');
  await page.click('#ballbar-run');
  await page.waitForSelector('#ballbar-results:not(.stale) #ballbar-iso .verdict-FAIL');
  await page.click('[data-tab="kinematics"]');
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#report-all')]);
  const html = readFileSync(await dl.path(), 'utf8');
  check(/\.html$/.test(dl.suggestedFilename()), `the report is an HTML file: ${dl.suggestedFilename()}`);

  // Open it offline in a fresh context: any request is a failure.
  const ctx = await page.context().browser().newContext();
  const requests = [];
  await ctx.route('**/*', (r) => {
    requests.push(r.request().url());
    return r.abort();
  });
  const p = await ctx.newPage();
  await p.setContent(html, { waitUntil: 'load' });
  check(requests.filter((u) => !u.startsWith('data:')).length === 0, `the report must load nothing: ${requests.join(', ')}`);
  const text = await p.textContent('body');
  check(/Date\s*\d{4}-\d\d-\d\d \d\d:\d\d:\d\d UTC/.test(text), 'the report states the date');
  check(/mtmotion core v\d+\.\d+/.test(text), 'the report states the software version');
  for (const id of ['ballbar', 'kinematics']) check(await p.$(`#report-${id}`), `the report has the ${id} section`);
  // Tabs and cards that were not run are left out, and named as such.
  for (const id of ['servo', 'toolpath']) check(!(await p.$(`#report-${id}`)), `the report must leave out the ${id} tab, which was not run`);
  check(/Not run \(left out\)\s*Servo[^;]*; Tool path/.test(text), 'the report names the tabs it left out');
  check(!/Rotary-axis alignment from your sections/.test(text), 'the alignment card, not run, is left out');
  check(!/5-axis NC compensation/.test(text), 'the 5-axis NC card, not run, is left out');
  check(/Machine\s*VMC-7 #1042/.test(text) && /Operator\s*A\. Ito/.test(text), 'the report states the machine and the operator');
  check(/G ≤ 1\.00 µm/.test(text) && /FAIL/.test(text), 'the ISO 230-4 block carries the tolerance verdict');
  check(/ISO 230-4 circular test/.test(text) && /G \[µm\]/.test(text), 'the report holds the ISO 230-4 block');
  check(/ISO 10791-6 cone-frustum/.test(text) && /min \[µm\]/.test(text), 'the report holds the ISO 10791-6 block');
  check(/Bar length\s*\[mm\]\s*:?\s*100/.test(text), 'the report lists the inputs with their values');
  const imgs = await p.$$eval('img', (is) => is.map((i) => [i.src.slice(0, 22), i.naturalWidth]));
  check(imgs.length >= 4 && imgs.every(([src, w]) => src === 'data:image/png;base64,' && w > 0), `plots are inlined PNG images that decode: ${JSON.stringify(imgs.slice(0, 5))}`);
  check(/@page\s*{\s*size:\s*A4/.test(html), 'the print stylesheet sets A4');
  check(!/<button|<input/.test(html), 'no controls in the report');
  await ctx.close();
}
