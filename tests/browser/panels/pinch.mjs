// Phones: a 2D plot (the ball bar's polar plot) says "pinch to zoom" (not "wheel to zoom") on a
// touch screen, a two-finger pinch zooms it, and a double-tap restores it.
export default async function (page, check) {
  const ctx = await page.context().browser().newContext({ viewport: { width: 390, height: 844 }, deviceScaleFactor: 2, isMobile: true, hasTouch: true });
  try {
    const p = await ctx.newPage();
    const problems = [];
    p.on('pageerror', (e) => problems.push(e.message));
    await p.goto(page.url());
    await p.waitForFunction(() => document.body.dataset.ready === 'true', null, { timeout: 90_000 });
    await p.click('[data-tab="ballbar"]');
    await p.waitForSelector('#ballbar-results:not(.stale) #ballbar-polar canvas');
    const hintText = await p.textContent('#ballbar-polar .chart-hint');
    check(/pinch to zoom/.test(hintText) && !/wheel/.test(hintText), `a phone should be told to pinch, hint says "${hintText}"`);
    const canvas = await p.$('#ballbar-polar canvas');
    await canvas.scrollIntoViewIfNeeded();
    const b = await canvas.boundingBox();
    const img = () => p.$eval('#ballbar-polar canvas', (c) => c.toDataURL());
    const before = await img();
    const cdp = await ctx.newCDPSession(p);
    const cx = b.x + b.width / 2;
    const cy = b.y + b.height / 2;
    const touch = (type, d) => cdp.send('Input.dispatchTouchEvent', { type, touchPoints: type === 'touchEnd' ? [] : [{ x: cx - d, y: cy, id: 1 }, { x: cx + d, y: cy, id: 2 }] });
    await touch('touchStart', 20);
    for (const d of [40, 60, 80, 100]) await touch('touchMove', d);
    await touch('touchEnd', 0);
    await p.waitForTimeout(100);
    check((await img()) !== before, 'a two-finger pinch should zoom the polar plot');
    await p.dblclick('#ballbar-polar canvas');
    await p.waitForTimeout(100);
    check((await img()) === before, 'a double-tap should restore the unzoomed view');
    check(problems.length === 0, `page errors: ${problems.join('; ')}`);
  } finally {
    await ctx.close();
  }
}
