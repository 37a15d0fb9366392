// A PNG dropped on the tool-path program (issue: it replaced the user's
// program with binary text and 100+ errors) is refused with one message
// that names the file and what it is; the program in the editor is
// unchanged, and a text program dropped after it loads.

/** A real PNG's first bytes: signature, IHDR of a 16×16 RGBA image, then bytes ≥ 0x80. */
function png() {
  const sig = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];
  const ihdr = [0, 0, 0, 13, 0x49, 0x48, 0x44, 0x52, 0, 0, 0, 16, 0, 0, 0, 16, 8, 6, 0, 0, 0, 0x1f, 0xf3, 0xff, 0x61];
  const body = Array.from({ length: 4000 }, (_, i) => (i * 151 + 0x80) & 0xff);
  return Buffer.from([...sig, ...ihdr, ...body]);
}

export default async function (page, check) {
  await page.click('[data-tab="toolpath"]');
  const before = await page.inputValue('#toolpath-nc');
  await page.setInputFiles('#toolpath-file', { name: 'photo.png', mimeType: 'image/png', buffer: png() });
  await page.waitForSelector('#toolpath-check .error-box');
  const msg = await page.textContent('#toolpath-check .error-box');
  check(/photo\.png was not loaded/.test(msg) && /a PNG image/.test(msg) && /unchanged/.test(msg), `the refusal should name photo.png and say it is a PNG image, says "${msg}"`);
  check((await page.inputValue('#toolpath-nc')) === before, 'the program must be unchanged after a PNG is dropped');
  check((await page.$$('#toolpath-check-errors li')).length === 0, 'no per-line errors for the bytes of an image');
  await page.setInputFiles('#toolpath-file', { name: 'square.nc', mimeType: 'text/plain', buffer: Buffer.from('G21 G90 G0 X0 Y0\nG1 X20 F600\nY10\nX0\nY0\nM30\n') });
  await page.waitForFunction(() => document.querySelector('#toolpath-nc').value.startsWith('G21 G90 G0 X0 Y0'));
  await page.waitForSelector('#toolpath-check-time');
}
