// Keyboard and phone: the tabs follow the WAI-ARIA pattern (arrows wrap,
// Home, End, aria-controls naming the panel, one tab in the Tab order);
// each tab is a history entry, so Back returns to the previous tab; on a
// phone (390×844) the tab bar is one line (< 10 % of the screen) and
// nothing makes the page scroll sideways (wide tables scroll in their card).
export default async function (page, check) {
  const selected = () => page.$eval('[role="tab"][aria-selected="true"]', (b) => b.dataset.tab);
  for (const name of ['servo', 'toolpath', 'ballbar', 'kinematics']) {
    const ctl = await page.getAttribute(`#tab-${name}`, 'aria-controls');
    check(ctl === `panel-${name}` && (await page.$(`#${ctl}[role="tabpanel"]`)), `tab ${name} should control panel-${name}, has ${ctl}`);
  }
  await page.focus('#tab-servo');
  await page.keyboard.press('ArrowRight');
  check((await selected()) === 'toolpath' && (await page.isVisible('#panel-toolpath')), `ArrowRight from servo should open toolpath, open: ${await selected()}`);
  check(await page.evaluate(() => document.activeElement.id === 'tab-toolpath'), 'focus follows the selected tab');
  await page.keyboard.press('End');
  check((await selected()) === 'kinematics', `End should open the last tab, open: ${await selected()}`);
  await page.keyboard.press('ArrowRight');
  check((await selected()) === 'servo', `ArrowRight on the last tab wraps to the first, open: ${await selected()}`);
  await page.keyboard.press('ArrowLeft');
  check((await selected()) === 'kinematics', `ArrowLeft on the first tab wraps to the last, open: ${await selected()}`);
  await page.keyboard.press('Home');
  check((await selected()) === 'servo', `Home should open the first tab, open: ${await selected()}`);
  const inOrder = await page.$$eval('[role="tab"]', (ts) => ts.filter((t) => t.tabIndex === 0).map((t) => t.dataset.tab));
  check(inOrder.length === 1 && inOrder[0] === 'servo', `only the selected tab is in the Tab order: ${inOrder}`);
  // History: servo → ballbar, then Back returns to servo (not out of the app).
  await page.click('#tab-ballbar');
  check((await selected()) === 'ballbar', 'a click opens the ball-bar tab');
  if (page.url().startsWith('http')) {
    await page.goBack();
    await page.waitForFunction(() => document.querySelector('[role="tab"][aria-selected="true"]').dataset.tab === 'servo');
    check((await selected()) === 'servo', 'Back returns to the previous tab');
  }

  // Phone.
  await page.setViewportSize({ width: 390, height: 844 });
  await page.click('#tab-servo');
  await page.waitForTimeout(200);
  const navH = await page.$eval('nav.tabs', (n) => n.getBoundingClientRect().height);
  check(navH < 0.1 * 844, `the tab bar should be one line on a phone, it is ${navH} px high`);
  for (const name of ['servo', 'toolpath', 'ballbar', 'kinematics']) {
    await page.click(`#tab-${name}`);
    await page.waitForTimeout(100);
    const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
    check(overflow <= 1, `${name}: no sideways page scroll on a phone (overflow ${overflow} px)`);
  }
}
