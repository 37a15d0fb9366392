// Browser test: serves dist/ on loopback, loads the page in headless Debian
// Chromium (playwright-core), waits for ready, and runs the shell checks and
// every panel test in tests/browser/panels/*.mjs. Fails on any console error,
// page error or request that would leave this machine. Screenshots go to
// tests/browser/screenshots/.
import { existsSync, mkdirSync, readdirSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../../scripts/static-server.mjs';

const here = new URL('.', import.meta.url);
const dist = fileURLToPath(new URL('../../dist/', here));
const shots = fileURLToPath(new URL('screenshots/', here));
if (!existsSync(`${dist}index.html`)) throw new Error('dist/ is missing: run ./scripts/build first');
mkdirSync(shots, { recursive: true });

const { server, url: base } = await startServer(dist, 0);
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run'],
});

let passed = 0;
let failed = 0;
const standaloneUrl = new URL('../../dist/mtmotion-standalone.html', here).href;
const local = (u) => u.startsWith(base) || u === standaloneUrl || u.startsWith('data:') || u.startsWith('blob:');

/** Opens a fresh page that records problems; returns { page, problems }. */
async function openPage(url, viewport = { width: 1366, height: 900 }) {
  const context = await browser.newContext({ viewport, acceptDownloads: true });
  const page = await context.newPage();
  const problems = [];
  page.on('console', (m) => m.type() === 'error' && problems.push(`console error: ${m.text()}`));
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  await context.route('**/*', (route) => {
    const u = route.request().url();
    if (local(u)) return route.continue();
    problems.push(`request leaves the machine: ${u}`);
    return route.abort();
  });
  await page.goto(url);
  await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 90_000 });
  return { page, problems, context };
}

// ONLY=alignment,servo runs just the tests whose name contains one of these.
const only = process.env.ONLY ? process.env.ONLY.split(',') : null;

async function run(name, fn, { url = base + 'index.html', viewport } = {}) {
  if (only && !only.some((o) => name.includes(o))) return;
  const t0 = Date.now();
  let ctx;
  try {
    const opened = await openPage(url, viewport);
    ctx = opened;
    const checks = [];
    const check = (cond, message) => {
      if (!cond) checks.push(message);
    };
    await fn(opened.page, check, base);
    await opened.page.screenshot({ path: `${shots}${name}.png`, fullPage: true });
    const problems = [...opened.problems, ...checks];
    if (problems.length) throw new Error(problems.join('\n  '));
    passed++;
    console.log(`ok   ${name} (${Date.now() - t0} ms)`);
  } catch (e) {
    failed++;
    if (ctx) await ctx.page.screenshot({ path: `${shots}${name}-failed.png`, fullPage: true }).catch(() => {});
    console.log(`FAIL ${name}: ${e.message}`);
  } finally {
    await ctx?.context.close();
  }
}

await run('shell', async (page, check) => {
  const status = await page.textContent('#status');
  check(/ready \(worker\)/.test(status), `the core should be ready in the Web Worker, status says "${status}"`);
  for (const p of ['servo', 'toolpath', 'ballbar', 'kinematics']) {
    await page.click(`[data-tab="${p}"]`);
    check(await page.isVisible(`#panel-${p}`), `panel ${p} should show after its tab is clicked`);
    check((await page.textContent(`#panel-${p} .lead`)).length > 40, `panel ${p} should say what it does`);
  }
  await page.click('[data-tab="servo"]');
  // The nmv5000 preset came through the worker from the Rust core.
  await page.waitForSelector('#servo-preset-table, #panel-servo table');
  const text = await page.textContent('#panel-servo');
  check(text.includes('725'), 'the servo panel should show the 725 N·m C-axis torque limit of the nmv5000 preset');
});

await run('tablet-layout', async (page, check) => {
  const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
  check(overflow <= 1, `no horizontal scrolling on a tablet (overflow ${overflow} px)`);
}, { viewport: { width: 768, height: 1024 } });

await run('deep-link-and-print', async (page, check) => {
  await page.click('[data-tab="kinematics"]');
  check(new URLSearchParams(new URL(page.url()).hash.slice(1)).get('tab') === 'kinematics', `the hash should record the panel, got ${page.url()}`);
  // A shared link restores the panel.
  await page.goto(base + 'index.html#tab=ballbar');
  await page.reload();
  await page.waitForFunction(() => document.body.dataset.ready === 'true');
  check(await page.isVisible('#panel-ballbar'), 'a #tab=ballbar link should open the ball-bar panel');
  check(!(await page.isVisible('#panel-servo')), 'only the linked panel shows');
  // Inputs are restored from the link and the panel's main action re-runs:
  // a longer acc/dec time must give a larger contour error.
  const maxErrorFor = async (hash) => {
    await page.goto(base + 'index.html' + hash);
    await page.reload();
    await page.waitForFunction(() => document.body.dataset.ready === 'true');
    await page.waitForSelector('#toolpath-max-error', { timeout: 60_000 });
    return parseFloat(await page.textContent('#toolpath-max-error'));
  };
  const short = await maxErrorFor('#tab=toolpath&toolpath-ta=20');
  const long = await maxErrorFor('#tab=toolpath&toolpath-ta=80');
  check((await page.inputValue('#toolpath-ta')) === '80', 'the link restores tA = 80 ms into its input');
  check(long > short, `the restored tA must be used: error at tA 80 ms (${long} µm) should exceed tA 20 ms (${short} µm)`);
  await page.emulateMedia({ media: 'print' });
  check(!(await page.isVisible('nav.tabs')), 'the print stylesheet hides the navigation');
  await page.screenshot({ path: `${shots}print.png`, fullPage: true });
  await page.emulateMedia({ media: 'screen' });
});

// The single-file page, opened straight from disk: same shell checks.
await run('standalone-file-shell', async (page, check) => {
  check(page.url().startsWith('file://'), 'the single-file page is opened through file://');
  const status = await page.textContent('#status');
  check(/ready \(worker\)/.test(status), `the inlined core should run in a blob worker from file://, status says "${status}"`);
  const text = await page.textContent('#panel-servo');
  check(text.includes('725'), 'the servo panel should show the nmv5000 preset from the inlined core');
}, { url: standaloneUrl });

// Documentation calculators (custom elements) in a docs-style page.
await run('embed-example', (await import('./embed.mjs')).default);

const panelDir = new URL('panels/', here);
for (const f of existsSync(panelDir) ? readdirSync(panelDir).filter((f) => f.endsWith('.mjs')).sort() : []) {
  const mod = await import(new URL(f, panelDir));
  const name = f.replace(/\.mjs$/, '');
  await run(`panel-${name}`, mod.default);
  // Every panel also works in the single-file page opened from disk.
  await run(`standalone-file-${name}`, mod.default, { url: standaloneUrl });
}

await browser.close();
server.close();
console.log(`\nbrowser: ${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
