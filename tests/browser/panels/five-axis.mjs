// Consistent 5-axis state: loading the S-shape selects the Pocket NC it was
// written for and its compensation headlines a reduction (thasana 80.73 %);
// the same program on the A–C trunnion is refused at the line and column of
// its first B word (the core's check); changing machine resets the
// cone-frustum centre to one inside the new machine's travel, and the
// cone-frustum test then runs there.
export default async function (page, check) {
  await page.click('[data-tab="kinematics"]');
  await page.waitForSelector('#kinematics-err-EX0C');
  check((await page.inputValue('#kinematics-machine')) === 'trunnion-ac', 'the page starts on the trunnion-ac');
  await page.click('#kinematics-sshape');
  await page.waitForFunction(() => document.querySelector('#kinematics-machine').value === 'pocketnc-v2-10' && document.querySelector('#kinematics-nc-input').value.includes('G1'));
  await page.click('#kinematics-nc-run');
  await page.waitForSelector('#kinematics-nc-out:not(.stale) :is(#kinematics-nc-reduction, #kinematics-nc-worse, .error-box)', { timeout: 120_000 });
  const red = await page.$('#kinematics-nc-reduction');
  check(red && parseFloat(await red.textContent()) >= 80, `the S-shape on the Pocket NC should show a reduction ≥ 80 %, shows: ${await page.textContent('#kinematics-nc-out')}`);

  // The same program on the A–C machine: refused where the first B word is.
  const nc = await page.inputValue('#kinematics-nc-input');
  const lines = nc.split('\n');
  const li = lines.findIndex((l) => /(^|\s)B-?\d/.test(l));
  const col = lines[li].search(/(?<=^|\s)B-?\d/) + 1;
  await page.selectOption('#kinematics-machine', 'trunnion-ac');
  await page.waitForFunction(() => document.querySelector('#kinematics-cx').value === '60');
  check([await page.inputValue('#kinematics-cx'), await page.inputValue('#kinematics-cy'), await page.inputValue('#kinematics-cz')].join() === '60,40,20', 'the cone-frustum centre is reset for the trunnion-ac');
  check(!(await page.$('#kinematics-nc-reduction')), 'the Pocket NC result is gone after the machine change');
  await page.click('#kinematics-nc-run');
  await page.waitForSelector('#kinematics-nc-out .error-box');
  const err = await page.textContent('#kinematics-nc-out .error-box');
  check(err.includes(`line ${li + 1}, column ${col}`) && err.includes("'B' word"), `the B word on the A–C machine should be refused at line ${li + 1}, column ${col}: "${err}"`);

  // Table-on-table: the reset centre is inside its travel (the test runs).
  await page.fill('#kinematics-cx', '-57');
  await page.selectOption('#kinematics-machine', 'table-on-table-bc');
  await page.waitForFunction(() => document.querySelector('#kinematics-cx').value === '60');
  await page.check('#kinematics-ideal');
  await page.click('#kinematics-cone-run');
  await page.waitForSelector('#kinematics-cone-out:not(.stale) :is(#kinematics-cone-max, .error-box)', { timeout: 120_000 });
  const coneErr = await page.$('#kinematics-cone-out .error-box');
  check(!coneErr, `the cone-frustum test should run at the reset centre on table-on-table-bc: ${coneErr && (await coneErr.textContent())}`);
}
