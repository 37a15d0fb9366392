// Shared links carry a pasted program: the tool-path program travels in the
// hash (deflated); opening the link restores it exactly and re-runs. A
// program too large for a link is not silently dropped: the opened link
// says it must be loaded again.
export default async function (page, check) {
  await page.click('[data-tab="toolpath"]');
  const program = 'G90 G21\nG01 X10 Y0 F1200\nG01 X10 Y10\nG02 X0 Y10 I-5 J0\nG01 X0 Y0\n';
  await page.fill('#toolpath-nc', program);
  await page.dispatchEvent('#toolpath-nc', 'change');
  await page.waitForFunction(() => location.hash.includes('toolpath-nc.z='));
  const link = page.url();
  const open = async (url) => {
    await page.goto(url);
    await page.reload();
    await page.waitForFunction(() => document.body.dataset.ready === 'true');
  };
  await open(link);
  check((await page.inputValue('#toolpath-nc')) === program, 'the shared link should restore the pasted program exactly');
  await page.waitForSelector('#toolpath-max-error', { timeout: 60_000 });

  // Too large for a link (random coordinates barely compress).
  let big = 'G90 G21\n';
  for (let i = 0; i < 6000; i++) big += `G01 X${(Math.random() * 100).toFixed(4)} Y${(Math.random() * 100).toFixed(4)} F1000\n`;
  await page.$eval('#toolpath-nc', (t, v) => {
    t.value = v;
    t.dispatchEvent(new Event('input', { bubbles: true }));
    t.dispatchEvent(new Event('change', { bubbles: true }));
  }, big);
  await page.waitForFunction(() => location.hash.includes('toolpath-nc.z=too-large'));
  await open(page.url());
  const note = await page.textContent('#panel-toolpath .link-note');
  check(/load the file again/.test(note || ''), `a link without the program should say to load it again: "${note}"`);
}
