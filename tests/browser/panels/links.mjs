// Shared links carry a pasted program: the tool-path program travels in the
// hash (deflated); opening the link restores it exactly and re-runs. A
// program too large for a link is not silently dropped: the opened link
// says it must be loaded again. A dropped ball-bar trace travels the same
// way: the opened link reads it again and shows the same fitted centre.
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

  // A dropped ball-bar trace travels in the link and is read again.
  await page.click('[data-tab="ballbar"]');
  const trace = ['angle_deg,deviation_um', ...Array.from({ length: 361 }, (_, i) => `${i},${(2 + 3 * Math.cos((i * Math.PI) / 180)).toFixed(4)}`)].join('\n');
  await page.waitForSelector('#ballbar-centre-x');
  const synthetic = await page.textContent('#ballbar-centre-x');
  const input = await page.$('#panel-ballbar .drop input[type=file]:not([multiple])');
  await input.setInputFiles({ name: 'shop-trace.csv', mimeType: 'text/csv', buffer: Buffer.from(trace) });
  await page.waitForFunction(() => /shop-trace\.csv: 1 run/.test(document.querySelector('#ballbar-file-info').textContent));
  // The file's run replaces the synthetic run's results: wait for it to
  // settle (not busy) with a centre other than the synthetic one.
  const settledOn = (before) => page.waitForFunction((b) => {
    const x = document.querySelector('#ballbar-centre-x');
    return x && !document.querySelector('#ballbar-results').hasAttribute('aria-busy') && x.textContent !== b;
  }, before, { timeout: 60_000 });
  await settledOn(synthetic);
  const centre = await page.textContent('#ballbar-centre-x');
  await page.waitForFunction(() => location.hash.includes('ballbar-trace.z=') && !location.hash.includes('too-large'));
  await open(page.url());
  await page.waitForFunction(() => /shop-trace\.csv: 1 run/.test(document.querySelector('#ballbar-file-info').textContent), null, { timeout: 60_000 });
  await page.waitForSelector('#ballbar-centre-x', { timeout: 60_000 });
  const again = await page.textContent('#ballbar-centre-x');
  check(again === centre && Math.abs(Number(centre) - 3) < 0.01, `the linked trace should give the same fitted centre X (3 µm): ${centre} then ${again}`);

  // A trace too large for a link is named, and the page asks for it again.
  const noisy = ['angle_deg,deviation_um', ...Array.from({ length: 20000 }, (_, i) => `${(i * 0.018).toFixed(3)},${(Math.random() * 10).toFixed(6)}`)].join('\n');
  const input2 = await page.$('#panel-ballbar .drop input[type=file]:not([multiple])');
  await input2.setInputFiles({ name: 'long-trace.csv', mimeType: 'text/csv', buffer: Buffer.from(noisy) });
  await page.waitForFunction(() => location.hash.includes('ballbar-trace.z=too-large'));
  await open(page.url());
  const traceNote = await page.textContent('#panel-ballbar .link-note');
  check(/long-trace\.csv/.test(traceNote || '') && /load it again/.test(traceNote || ''), `a link without the trace should name it and say to load it again: "${traceNote}"`);
}
