// Screenshots of every tab at desktop (1366×900) and phone (390×844) size,
// after the tab's main action has run, into docs/screenshots/; for the
// tool path also its 3D view (toolpath-3d-*.png). Run after
// ./scripts/build: node tests/browser/screenshots.mjs
import { mkdirSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { join } from 'node:path';
import { startServer } from '../../scripts/static-server.mjs';
import { corpusDir, corpusMissing } from '../support/corpus.mjs';

const dist = fileURLToPath(new URL('../../dist/', import.meta.url));
const out = fileURLToPath(new URL('../../docs/screenshots/', import.meta.url));
mkdirSync(out, { recursive: true });
const { server, url } = await startServer(dist, 0);
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', args: ['--headless', '--no-sandbox', '--disable-gpu'] });
const sizes = { desktop: { width: 1366, height: 900 }, phone: { width: 390, height: 844 } };
for (const [size, viewport] of Object.entries(sizes)) {
  const page = await browser.newPage({ viewport, deviceScaleFactor: 1 });
  await page.goto(url + 'index.html');
  await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 90_000 });
  for (const tab of ['servo', 'toolpath', 'ballbar', 'kinematics']) {
    await page.click(`[data-tab="${tab}"]`);
    const run = await page.$(`#panel-${tab} [data-run]`);
    if (run) {
      await run.click();
      await page.waitForFunction((t) => !document.querySelector(`#panel-${t} .stale`), tab, { timeout: 120_000 });
      await page.waitForTimeout(300);
    }
    await page.evaluate(() => window.scrollTo(0, 0));
    await page.screenshot({ path: `${out}${tab}-${size}.png` });
    console.log(`docs/screenshots/${tab}-${size}.png`);
    if (tab === 'toolpath') {
      // The 3D path view with the worst spots marked and the worst one's
      // line selected in the editor and highlighted in the view.
      await page.waitForSelector('#toolpath-path3d .path3d-mark');
      await page.click('#toolpath-worst a[data-rank="1"][data-kind="cutting"]');
      await page.waitForTimeout(300);
      const view = await page.$('#toolpath-path');
      await view.scrollIntoViewIfNeeded();
      await page.waitForTimeout(300);
      await view.screenshot({ path: `${out}toolpath-3d-${size}.png` });
      console.log(`docs/screenshots/toolpath-3d-${size}.png`);
    }
  }
  await page.close();
}
// The 3D view of a real 35k-line raster program (the shared corpus's
// CAMotics cameo, when it is there), at desktop size.
if (corpusDir) {
  const page = await browser.newPage({ viewport: sizes.desktop, deviceScaleFactor: 1 });
  await page.goto(url + 'index.html');
  await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 90_000 });
  await page.click('[data-tab="toolpath"]');
  await page.setInputFiles('#toolpath-file', join(corpusDir, 'camotics_cameo.nc'));
  await page.waitForFunction(() => document.querySelector('#toolpath-nc').value.split('\n').length > 35_000, null, { timeout: 60_000 });
  await page.click('#toolpath-run');
  await page.waitForSelector('#toolpath-path3d .path3d-mark', { timeout: 120_000 });
  await page.waitForTimeout(1500);
  const view = await page.$('#toolpath-path');
  await view.scrollIntoViewIfNeeded();
  await view.screenshot({ path: `${out}toolpath-3d-cameo-desktop.png` });
  console.log('docs/screenshots/toolpath-3d-cameo-desktop.png');
  await page.close();
} else console.log(`no cameo screenshot: ${corpusMissing}`);
await browser.close();
server.close();
