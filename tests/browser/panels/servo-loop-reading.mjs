// Servo panel: the loop reading (machinePreset('nmv5000', reading)) refills
// the parameter table with that reading's values, taken from the JS API in
// Node for comparison: 'kppText' sets Kpp = 30 on every axis, and
// 'inertiaAtLoad' puts X's J on the motor side of the 16 mm screw; back to
// 'table' restores Table 1 as printed.
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const mt = await import(new URL('../../../pkg/mtmotion.js', import.meta.url));
mt.initSync({ module: readFileSync(fileURLToPath(new URL('../../../pkg/mtmotion_bg.wasm', import.meta.url))) });

export default async function (page, check) {
  await page.click('[data-tab="servo"]');
  await page.waitForSelector('#servo-loop-reading');
  const readings = await page.$$eval('#servo-loop-reading option', (os) => os.map((o) => o.value));
  check(JSON.stringify(readings) === JSON.stringify(mt.machinePreset('nmv5000').loopReadings), `the readings offered should be the core's, shows ${readings}`);
  for (const reading of ['kppText', 'inertiaAtLoad', 'table']) {
    const want = mt.machinePreset('nmv5000', reading);
    await page.selectOption('#servo-loop-reading', reading);
    await page.waitForFunction(([v]) => Number(document.querySelector('#servo-p-x-j').value) === v, [want.axes.x.j]);
    for (const a of ['x', 'y', 'c']) {
      for (const f of ['j', 'kpp', 'kvp']) {
        const shown = Number(await page.inputValue(`#servo-p-${a}-${f}`));
        check(shown === want.axes[a][f], `${reading}: ${a}.${f} should be ${want.axes[a][f]}, shows ${shown}`);
      }
    }
  }
}
