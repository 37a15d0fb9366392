// Report of the tool-path tab after a simulation and a reverse
// compensation: each 3D view (the simulation's, and the compensation's
// before/after) is in the report as a PNG image of what it showed, not a
// blank canvas, captioned with its legend; the before/after switch reads
// as which one was shown.
import { readFileSync } from 'node:fs';

export default async function (page, check) {
  await page.click('[data-tab="toolpath"]');
  await page.click('#toolpath-run');
  await page.waitForSelector('#toolpath-path3d .path3d-mark', { timeout: 60_000 });
  await page.click('#toolpath-compensate');
  await page.waitForSelector('#toolpath-comp-path3d .path3d-mark', { timeout: 60_000 });
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#report-all')]);
  const html = readFileSync(await dl.path(), 'utf8');
  const ctx = await page.context().browser().newContext();
  try {
    await ctx.route('**/*', (r) => r.abort());
    const p = await ctx.newPage();
    await p.setContent(html, { waitUntil: 'load' });
    // Pixels of each 3D image that are not the view's background (#fbfbfd).
    const views = await p.$$eval('#report-toolpath img[alt="tool path in 3D"]', (imgs) => imgs.map((img) => {
      const c = document.createElement('canvas');
      c.width = img.naturalWidth;
      c.height = img.naturalHeight;
      const g = c.getContext('2d');
      g.drawImage(img, 0, 0);
      const d = g.getImageData(0, 0, c.width, c.height).data;
      let drawn = 0;
      for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - 251) + Math.abs(d[i + 1] - 251) + Math.abs(d[i + 2] - 253) > 30) drawn++;
      return { w: c.width, drawn, caption: img.closest('figure')?.querySelector('figcaption')?.textContent ?? '' };
    }));
    check(views.length === 2, `the report should hold both 3D views as images: ${views.length}`);
    for (const v of views) check(v.w > 0 && v.drawn > 500 && /contour error 0/.test(v.caption), `a 3D view's image should show the paths (${v.drawn} drawn pixels) with its legend: "${v.caption.slice(0, 60)}"`);
    check(!(await p.$('#report-toolpath canvas')), 'no blank canvas in the report');
    const text = (await p.textContent('#report-toolpath')) ?? '';
    check(/○ before \(original program\)\s*◉ after/.test(text), `the report says the after run was shown: ${text.match(/Show:.{0,80}/)?.[0]}`);
  } finally {
    await ctx.close();
  }
}
