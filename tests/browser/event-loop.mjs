// The page's responsiveness, measured in the page: shared by the browser
// tests that load large inputs.

/** Largest event-loop delay seen while `work` runs, in ms (a 20 ms probe). */
export async function worstDelay(page, work) {
  await page.evaluate(() => {
    const w = /** @type {any} */ (window);
    w.__worst = 0;
    w.__last = performance.now();
    w.__probe = setInterval(() => {
      const now = performance.now();
      w.__worst = Math.max(w.__worst, now - w.__last - 20);
      w.__last = now;
    }, 20);
  });
  await work();
  return page.evaluate(() => {
    const w = /** @type {any} */ (window);
    clearInterval(w.__probe);
    return w.__worst;
  });
}

/** The main thread while `work` runs: the worst event-loop delay
 * (worstDelay) and the browser's Long Tasks (PerformanceObserver
 * 'longtask': every task of 50 ms or more), in ms. */
export async function mainThread(page, work) {
  await page.evaluate(() => {
    const w = /** @type {any} */ (window);
    w.__longTasks = [];
    w.__longObserver = new PerformanceObserver((list) => w.__longTasks.push(...list.getEntries().map((e) => e.duration)));
    w.__longObserver.observe({ type: 'longtask' });
  });
  const delay = await worstDelay(page, work);
  const tasks = await page.evaluate(() => {
    const w = /** @type {any} */ (window);
    w.__longObserver.disconnect();
    return w.__longTasks;
  });
  return { delay, tasks, longest: Math.max(0, ...tasks) };
}
