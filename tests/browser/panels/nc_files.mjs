// Tool-path panel, several files : dropping a subprogram file
// together with its main program (in either order) loads the program that
// ends with M30 as the main one, names it, and the check reads the
// subprogram from the other file (O2000 moves 5 mm at F100 → 3 s; main 10 mm
// at F600 → 1 s; total 4 s). An error in the subprogram file names that file.
export default async function (page, check) {
  await page.click('[data-tab="toolpath"]');
  await page.waitForSelector('#toolpath-nc');
  const sub = { name: 'O2000.nc', mimeType: 'text/plain', buffer: Buffer.from('O2000\nG91 G1 X5 F100\nG90\nM99\n') };
  const main = { name: 'main.nc', mimeType: 'text/plain', buffer: Buffer.from('G21 G90\nG1 X10 F600\nM98 P2000\nM30\n') };
  await page.setInputFiles('#toolpath-file', [sub, main]);
  await page.waitForSelector('#toolpath-files-main', { timeout: 30_000 });
  const named = await page.textContent('#toolpath-files-main');
  check(named.includes('main.nc'), `main program named: ${named}`);
  await page.waitForSelector('#toolpath-check-time', { timeout: 30_000 });
  const t = parseFloat(await page.textContent('#toolpath-check-time'));
  check(Math.abs(t - 4) < 1e-9, `summary with the subprogram from the other file: ${t} s (expected 4 s)`);
  const bad = { name: 'O2000.nc', mimeType: 'text/plain', buffer: Buffer.from('O2000\nG1 X\nM99\n') };
  await page.setInputFiles('#toolpath-file', [main, bad]);
  await page.waitForSelector('#toolpath-check-errors li', { timeout: 30_000 });
  const err = await page.textContent('#toolpath-check-errors');
  check(err.includes('O2000.nc, line 2, column 4'), `error names the file: ${err}`);
}
