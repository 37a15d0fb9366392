// Kinematics panel: an ideal machine with ideal servos reads 0 µm on the
// cone-frustum test (analytic: no error, no deviation), and compensating the
// S-shape program on a Monte-Carlo Pocket NC cuts the error std by ≥ 80 %
// (thasana: 80.73 %). "Load example errors" fills the preset's illustrative
// errors (location errors and backlash, sent as `errors` and `drives`) and re-runs: the shown largest bar deviation must exceed 1 µm and
// equal the JS API's for the same inputs, computed in a fresh instance (in
// the page when served over http; in Node from pkg/ for the file:// page,
// where browsers block module imports).
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const COMBOS = [[15, 'perpendicular'], [15, 'parallel'], [45, 'perpendicular'], [45, 'parallel']];

/** Largest |bar deviation| (mm) of the panel's four runs, from the JS API. */
function worstOf(mt, machine, inputs) {
  const { exampleErrors: errors, exampleDrives: drives } = mt.machinePreset(machine);
  const runs = COMBOS.map(([theta, method]) => mt.coneFrustumTest({ machine, halfApexDeg: theta, method, errors, drives, ...inputs }));
  return Math.max(...runs.map((r) => Math.max(Math.abs(r.minDeviation), Math.abs(r.maxDeviation))));
}

async function expectedWorst(page, machine, inputs) {
  if (page.url().startsWith('http')) {
    return page.evaluate(async ([machine, inputs, combos]) => {
      const mt = await import('./pkg/mtmotion.js');
      await mt.default({ module_or_path: new URL('./pkg/mtmotion_bg.wasm', location.href) });
      const { exampleErrors: errors, exampleDrives: drives } = mt.machinePreset(machine);
      const runs = combos.map(([theta, method]) => mt.coneFrustumTest({ machine, halfApexDeg: theta, method, errors, drives, ...inputs }));
      return Math.max(...runs.map((r) => Math.max(Math.abs(r.minDeviation), Math.abs(r.maxDeviation))));
    }, [machine, inputs, COMBOS]);
  }
  const mt = await import(new URL('../../../pkg/mtmotion.js', import.meta.url));
  mt.initSync({ module: readFileSync(fileURLToPath(new URL('../../../pkg/mtmotion_bg.wasm', import.meta.url))) });
  return worstOf(mt, machine, inputs);
}

export default async function (page, check) {
  await page.click('[data-tab="kinematics"]');
  await page.waitForSelector('#kinematics-err-EX0C');
  await page.check('#kinematics-ideal');
  await page.click('#kinematics-cone-run');
  await page.waitForSelector('#kinematics-cone-out:not(.stale) #kinematics-cone-max', { timeout: 120_000 });
  const max = parseFloat(await page.textContent('#kinematics-cone-max'));
  check(Number.isFinite(max) && Math.abs(max) < 1e-3, `ideal machine should read 0 µm, shows ${max} µm`);
  const rows = await page.$$eval('#kinematics-cone-table tbody tr', (r) => r.length);
  check(rows === 4, `four runs (15°/45° × perpendicular/parallel) expected, got ${rows}`);
  // Example errors, still with ideal servos: the run above read 0 µm, so
  // all of the deviation is the example errors' (the servo models at the
  // default centre saturate the C torque at 15° and read tens of mm).
  await page.click('#kinematics-example');
  await page.waitForSelector('#kinematics-cone-out:not(.stale) #kinematics-cone-max', { timeout: 120_000 });
  const ex = parseFloat(await page.textContent('#kinematics-cone-max'));
  const inputs = { inclinationDeg: 10, barLength: 100, feed: 1000, centre: [60, 40, 20], idealServo: true, points: 1440 };
  const want = 1e3 * (await expectedWorst(page, 'trunnion-ac', inputs));
  check(ex > 1, `example errors should show a bar deviation > 1 µm, shows ${ex} µm`);
  check(Math.abs(ex - want) <= 5.1e-5 + 1e-9 * Math.abs(want), `shown ${ex} µm should equal the JS API's ${want} µm for the same inputs (shown to 4 decimals)`);
  const shown3d = await page.$$eval('#kinematics-path3d canvas', (c) => c.length);
  check(shown3d === 1, 'the 3D spindle-ball path view is drawn');
  await page.selectOption('#kinematics-machine', 'pocketnc-v2-10');
  await page.waitForFunction(() => document.querySelector('#kinematics-nc-input').value.includes('G1'));
  await page.click('#kinematics-nc-run');
  await page.waitForSelector('#kinematics-nc-out:not(.stale) #kinematics-nc-reduction', { timeout: 120_000 });
  const red = parseFloat(await page.textContent('#kinematics-nc-reduction'));
  check(red >= 80, `compensation should cut the std by ≥ 80 %, shows ${red} %`);
  // Several Monte-Carlo runs (on the study pool where there is one): the
  // first run is the single run above (same seed), and each run gets a bar.
  await page.fill('#kinematics-mc-runs', '3');
  await page.click('#kinematics-nc-run');
  await page.waitForSelector('#kinematics-nc-out:not(.stale) #kinematics-mc-runs-chart canvas', { timeout: 120_000 });
  const first = parseFloat(await page.textContent('#kinematics-nc-reduction'));
  check(first === red, `the first of 3 runs should repeat the single run's ${red} %, shows ${first} %`);
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#kinematics-mc-download')]);
  const csv = readFileSync(await dl.path(), 'utf8').trim().split('\n');
  check(csv.length === 4 && csv[0].startsWith('seed,') && csv[1].startsWith('42,') && csv[3].startsWith('44,'), `the CSV should hold a header and seeds 42–44, got ${csv.slice(0, 2).join(' | ')}`);
  check(Math.abs(Number(csv[1].split(',').at(-1)) - red) < 1e-3, `the CSV's first total (${csv[1]}) should be the shown ${red} %`);
  await page.fill('#kinematics-mc-runs', '0');
  await page.click('#kinematics-nc-run');
  await page.waitForSelector('#kinematics-nc-out .error-box');
  const err = await page.textContent('#kinematics-nc-out .error-box');
  check(/whole number from 1 to 1000/.test(err), `0 runs should be refused in words, shows: ${err}`);
  await page.fill('#kinematics-mc-runs', '1');
}
