// Flat heap in the page: the servo panel's Simulate (six uPlot charts) and
// the tool path's Simulate (canvas charts) each run 20 times after a
// warm-up. The live ResizeObservers (observe() minus disconnect(), counted
// by a wrapper installed before the page loads) must not grow at all: every
// redraw replaces its chart's observer (www/lib/plot.js observe()). The JS
// heap after a forced garbage collection (CDP HeapProfiler.collectGarbage,
// Runtime.getHeapUsage) may grow by at most 2 MiB over the 20 runs; one
// kept result of these runs is hundreds of KiB (the servo run's series are
// 2 × 15 Float64Arrays of 2,000 samples, 480 KiB), so 20 kept results
// would be 10 MiB or more.
const WARMUP = 3;
const RUNS = 20;
const HEAP_BOUND = 2 * 1024 * 1024;

function countObservers() {
  const live = { n: 0 };
  window.__liveResizeObservers = live;
  const Native = window.ResizeObserver;
  window.ResizeObserver = class extends Native {
    observe(...a) {
      if (!this.__counted) {
        this.__counted = true;
        live.n++;
      }
      return super.observe(...a);
    }
    disconnect() {
      if (this.__counted) {
        this.__counted = false;
        live.n--;
      }
      return super.disconnect();
    }
  };
}

async function runOnce(page, button, area) {
  await page.click(button);
  // The run state marks the area busy from the click until the results are drawn.
  await page.waitForFunction((sel) => !document.querySelector(sel)?.hasAttribute('aria-busy'), area, { timeout: 60_000 });
}

export default async function (page, check) {
  await page.addInitScript(countObservers);
  await page.reload();
  await page.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 90_000 });
  const cdp = await page.context().newCDPSession(page);
  const probe = async () => {
    await cdp.send('HeapProfiler.collectGarbage');
    const { usedSize } = await cdp.send('Runtime.getHeapUsage');
    return { observers: await page.evaluate(() => window.__liveResizeObservers.n), heap: usedSize };
  };
  for (const [tab, button, area] of [
    ['servo', '#servo-run', '#servo-charts'],
    ['toolpath', '#toolpath-run', '#toolpath-out'],
  ]) {
    await page.click(`[data-tab="${tab}"]`);
    for (let i = 0; i < WARMUP; i++) await runOnce(page, button, area);
    const before = await probe();
    for (let i = 0; i < RUNS; i++) await runOnce(page, button, area);
    const after = await probe();
    const grew = after.heap - before.heap;
    console.log(`     ${tab}: ${before.observers} → ${after.observers} live ResizeObservers, JS heap ${(grew / 1024).toFixed(0)} KiB over ${RUNS} runs`);
    check(before.observers > 0, `${tab}: the charts should observe their size (counted ${before.observers} observers)`);
    check(after.observers === before.observers, `${tab}: live ResizeObservers grew from ${before.observers} to ${after.observers} over ${RUNS} runs`);
    check(grew <= HEAP_BOUND, `${tab}: JS heap grew by ${(grew / 1024).toFixed(0)} KiB over ${RUNS} runs (bound ${HEAP_BOUND / 1024} KiB)`);
  }
}
