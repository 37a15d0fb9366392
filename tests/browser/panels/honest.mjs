// Honest numbers: a ball-bar trace of pure noise (uniform ±2 µm from the
// core's synthetic generator, run here in Node) shows no reversal spike and
// a backlash of 0 with its stated resolution, and no value in exponent
// notation (numerical noise such as 3.91e-13 µm).
import { readFileSync } from 'node:fs';
import * as mt from '../../../pkg/mtmotion.js';

mt.initSync({ module: readFileSync(new URL('../../../pkg/mtmotion_bg.wasm', import.meta.url)) });

const t = mt.syntheticBallbarTrace({ noise: 0.002 });
const lines = ['angle_deg,deviation_um,direction'];
for (const r of t.runs) for (let i = 0; i < r.angleRad.length; i++) lines.push(`${(r.angleRad[i] * 180) / Math.PI},${r.deviation[i] * 1e3},${r.direction === 'ccw' ? 1 : -1}`);

export default async function (page, check) {
  await page.click('[data-tab="ballbar"]');
  const input = await page.$('#panel-ballbar .drop input[type=file]:not([multiple])');
  await input.setInputFiles({ name: 'noise.csv', mimeType: 'text/csv', buffer: Buffer.from(lines.join('\n') + '\n') });
  await page.waitForFunction(() => /noise\.csv: 2 run/.test(document.querySelector('#ballbar-file-info').textContent));
  await page.waitForSelector('#ballbar-results:not(.stale) #ballbar-diagnostics');
  const diag = await page.textContent('#ballbar-diagnostics');
  check(!/Reversal spike (CCW|CW)/.test(diag), `pure noise must show no reversal spike: ${diag}`);
  check(/none above the trace's noise threshold/.test(diag), 'the table should say no spike stands above the noise threshold');
  check(/Backlash X0 \(below [\d.]+ µm/.test(diag) && /Backlash Y0 \(below [\d.]+ µm/.test(diag), `pure noise must show backlash 0 with its resolution: ${diag}`);
  const shown = (await page.textContent('#ballbar-diagnostics')) + (await page.textContent('#ballbar-iso'));
  check(!/\de-\d/.test(shown), `no value in exponent notation: ${shown}`);
}
