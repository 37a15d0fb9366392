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
const local = (u) => u.startsWith(base) || u.startsWith('data:') || u.startsWith('blob:');

/** Opens a fresh page that records problems; returns { page, problems }. */
export async function openPage(path = 'index.html', viewport = { width: 1366, height: 900 }) {
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
  await page.goto(base + path);
  await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 90_000 });
  return { page, problems, context };
}

async function run(name, fn, viewport) {
  const t0 = Date.now();
  let ctx;
  try {
    const opened = await openPage('index.html', viewport);
    ctx = opened;
    const checks = [];
    const check = (cond, message) => {
      if (!cond) checks.push(message);
    };
    await fn(opened.page, check);
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
}, { width: 768, height: 1024 });

const panelDir = new URL('panels/', here);
for (const f of existsSync(panelDir) ? readdirSync(panelDir).filter((f) => f.endsWith('.mjs')).sort() : []) {
  const mod = await import(new URL(f, panelDir));
  await run(`panel-${f.replace(/\.mjs$/, '')}`, mod.default);
}

await browser.close();
server.close();
console.log(`\nbrowser: ${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
