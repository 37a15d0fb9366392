// Ball bar & alignment panel: a synthetic trace with a known centre offset and
// backlash is analysed in the page; the shown fitted centre and the ISO 230-4
// diagnostics must return the values put in, and the paper's Fig. 7 example
// must show an unbiased centre at 360°. A measured-like X/Y capture (time
// column, 90° lead-in from rest, 2 s standstill, centre off 0, arc from
// 23°) is trimmed, and the page says what was trimmed, about which centre,
// with thresholds and no sub-resolution raw number (e-NN).

/** X/Y at 1 kHz: R 50 mm about (12.3, −4.56) mm, 3000 mm/min, ovality 3 µm. */
function capture() {
  const R = 50;
  const w = 3000 / 60 / R; // rad/s
  const lines = ['time [s],X [mm],Y [mm]'];
  let t = 0;
  const put = (a) => {
    const r = R + 0.003 * Math.sin(2 * a);
    lines.push(`${t.toFixed(4)},${(12.3 + r * Math.cos(a)).toFixed(7)},${(-4.56 + r * Math.sin(a)).toFixed(7)}`);
    t += 1e-3;
  };
  const a0 = (23 * Math.PI) / 180;
  const span = Math.PI / 2;
  const lead = (2 * span) / w; // s, from rest at constant acceleration
  for (let s = 0; s < lead; s += 1e-3) put(a0 - span + 0.5 * (w / lead) * s * s);
  const n = Math.round((2 * Math.PI) / (w * 1e-3));
  for (let i = 0; i < n; i++) put(a0 + w * 1e-3 * i);
  for (let i = 0; i < n; i++) put(a0 + 2 * Math.PI - w * 1e-3 * i);
  for (let i = 0; i < 2000; i++) put(a0);
  return lines.join('\n') + '\n';
}

export default async function (page, check) {
  await page.click('[data-tab="ballbar"]');
  await page.waitForSelector('#ballbar-iso');
  // Full circle, centre (15, −8) µm, backlash X 4 µm, no motion harmonics.
  await page.fill('#ballbar-range', '360');
  await page.fill('#ballbar-offset-x', '15');
  await page.fill('#ballbar-offset-y', '-8');
  await page.fill('#ballbar-backlash-x', '4');
  await page.fill('#ballbar-harmonics-input', '3:2');
  await page.click('#ballbar-run');
  await page.waitForFunction(() => document.querySelector('#ballbar-centre-x')?.textContent && !document.querySelector('#ballbar-results').classList.contains('stale'));
  const cx = Number(await page.textContent('#ballbar-centre-x'));
  const cy = Number(await page.textContent('#ballbar-centre-y'));
  // Neither the backlash signature sign(sin θ)·cos θ nor the trefoil has a
  // first harmonic, so the least-squares centre is the offset put in.
  check(Math.abs(cx - 15) < 0.05 && Math.abs(cy + 8) < 0.05, `fitted centre should be near (15, −8) µm, shows (${cx}, ${cy})`);
  const diag = await page.textContent('#ballbar-diagnostics');
  const m = /Backlash X\s*([-\d.]+) µm/.exec(diag);
  check(m && Math.abs(Number(m[1]) - 4) < 0.1, `backlash X should read 4 µm, table says: ${m && m[1]}`);
  const iso = await page.textContent('#ballbar-iso');
  check(/CCW/.test(iso) && /CW/.test(iso), 'the ISO 230-4 table should have CCW and CW rows');
  // Trefoil 2 µm: G ≥ 4 µm per direction (plus the backlash steps).
  const g = Number((await page.$$eval('#ballbar-iso tbody tr td:nth-child(2)', (tds) => tds.map((t) => t.textContent)))[0]);
  check(g >= 4 && g < 9, `G of the CCW run should be about 4–8 µm, shows ${g}`);
  check(await page.isVisible('#ballbar-sweep'), 'the travel-range sweep should be drawn');
  // Row thresholds: every diagnostic names what it was compared with.
  check(/3 standard errors/.test(diag) && /critical/.test(diag) && /Run-model residual RMS/.test(diag), `diagnostic rows should state their thresholds: ${diag}`);
  // A capture with a lead-in and a standstill: trimmed, and said so.
  await page.fill('#ballbar-radius', '50');
  const input = await page.$('#panel-ballbar .drop input[type=file]:not([multiple])');
  await input.setInputFiles({ name: 'capture.csv', mimeType: 'text/csv', buffer: Buffer.from(capture()) });
  await page.waitForFunction(() => /capture\.csv: 2 run/.test(document.querySelector('#ballbar-file-info').textContent));
  await page.waitForSelector('#ballbar-results:not(.stale) #ballbar-trim');
  const trim = await page.textContent('#ballbar-trim');
  check(/Trimmed to the constant-feed part/.test(trim) && /lead-in lines \d+–/.test(trim) && /standstill/.test(trim), `the trimmed note should list the lead-in and the standstill: ${trim}`);
  check(/Feed 3000 mm\/min \(the plateau's median speed\)/.test(trim), `the feed should be the plateau's, 3000 mm/min: ${trim}`);
  check(/own least-squares centre \(12\.3000, -4\.5600\) mm/.test(trim), `the centre used should be named: ${trim}`);
  const fdiag = await page.textContent('#ballbar-diagnostics');
  check(/0 by construction/.test(fdiag), `the centre offset of a trace about its own LSC is 0 by construction: ${fdiag}`);
  const results = await page.textContent('#ballbar-results');
  const raw = /\d(\.\d+)?e-\d{2,}/.exec(results);
  check(!raw, `no sub-resolution raw number in the results: ${raw && results.slice(Math.max(0, raw.index - 80), raw.index + 20)}`);
  // The paper's Fig. 7 example: at 360° the estimate is unbiased.
  await page.click('#ballbar-example-run');
  await page.waitForSelector('#ballbar-paper-table');
  const rows = await page.$$eval('#ballbar-paper-table tbody tr', (trs) => trs.map((tr) => Array.from(tr.children, (td) => td.textContent)));
  const r360 = rows.find((r) => r[1] === '360');
  check(r360 && Math.abs(Number(r360[3])) < 0.01, `Fig. 7 at 360° should show ≈ 0 µm, row: ${JSON.stringify(r360)}`);
}
