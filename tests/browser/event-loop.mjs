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
