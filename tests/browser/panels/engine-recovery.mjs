// The engine survives what would otherwise leave the page dead, and links
// cannot start work with values the inputs would refuse:
// - a trap inside the wasm instance (simulated through the worker's test
//   hook) fails that one call with a message in words, the worker is
//   replaced, and the next call answers;
// - a call over its time limit and a cancelled call are stopped, and the
//   engine answers the next call;
// - a deep link whose value is outside an input's options is not applied
//   and runs nothing, and says why.
export default async function (page, check) {
  const call = (fn, args, opts) =>
    page.evaluate(
      ([fn, args, opts]) => {
        const o = { ...opts };
        let ctl;
        if (o.abortAfterMs !== undefined) {
          ctl = new AbortController();
          o.signal = ctl.signal;
          setTimeout(() => ctl.abort(), o.abortAfterMs);
          delete o.abortAfterMs;
        }
        return globalThis.mtmotion.api.call(fn, args, o).then(
          (r) => ({ ok: true, name: r?.name }),
          (e) => ({ ok: false, message: e.message }),
        );
      },
      [fn, args, opts ?? {}],
    );
  const mode = await page.evaluate(() => globalThis.mtmotion.api.mode);
  if (mode === 'worker') {
    const trap = await call('__simulateTrap', []);
    check(!trap.ok && /failed inside the engine.*restarted/.test(trap.message), `a trap should fail with a message in words, got ${JSON.stringify(trap)}`);
    const after = await call('machinePreset', ['nmv5000']);
    check(after.ok && after.name === 'nmv5000', `the engine should answer after a trap, got ${JSON.stringify(after)}`);
    const restarts = await page.evaluate(() => globalThis.mtmotion.api.restarts);
    check(restarts === 1, `one worker restart expected, counted ${restarts}`);

    const program = await page.evaluate(() => globalThis.mtmotion.api.call('toolpathExample', ['arcs']).catch(() => null));
    check(typeof program === 'string' && program.length > 100, 'toolpathExample should give the example program');
    {
      const text = program;
      const slow = await call('simulateToolPath', [text, { dt: 1e-4 }], { timeoutMs: 1 });
      check(!slow.ok && /took longer than/.test(slow.message), `a call over its time limit should be stopped, got ${JSON.stringify(slow)}`);
      const cancelled = await call('simulateToolPath', [text, { dt: 1e-4 }], { abortAfterMs: 0 });
      check(!cancelled.ok && cancelled.message === 'cancelled', `a cancelled call should say so, got ${JSON.stringify(cancelled)}`);
    }
    const again = await call('machinePreset', ['nmv5000']);
    check(again.ok, `the engine should answer after a timeout and a cancel, got ${JSON.stringify(again)}`);
  }
  const before = await page.innerHTML('#servo-results');
  await page.evaluate(() => {
    location.hash = '#tab=servo&servo-j1=x';
  });
  await page.waitForFunction(() => /This link was not applied/.test(document.getElementById('status').textContent));
  const status = await page.textContent('#status');
  check(/'x' is not one of/.test(status), `the status should name the bad value, shows "${status}"`);
  await page.waitForTimeout(300);
  check((await page.innerHTML('#servo-results')) === before, 'a rejected link must not run the panel');
}
