// A pool of Web Workers (one per core: navigator.hardwareConcurrency) for
// the long studies, with progress and cancel. The core computes; this file
// only schedules and concatenates: every study is split into independent
// core calls (one K_FFP sweep point, a chunk of travel ranges or angles, one
// Monte-Carlo seed), each a pure function of its arguments, so the results
// are identical whatever the worker count (tests/node/pool.test.mjs).
//
//   const pool = createPool();                    // or createPool({ size: 1 })
//   const points = await travelRangeSweep(pool, config, { onProgress, signal });
//   pool.close();
//
// `spawn` makes one worker: by default a module worker running
// www/pool-worker.js; the Node test passes worker_threads instead.

/** @typedef {{ onProgress?: (done: number, total: number) => void, signal?: AbortSignal }} MapOptions */

const defaultSpawn = () => new Worker(new URL('../pool-worker.js', import.meta.url), { type: 'module' });

/** Creates a pool of `size` workers (started lazily, on the first task). */
export function createPool({ size = globalThis.navigator?.hardwareConcurrency || 2, spawn = defaultSpawn } = {}) {
  size = Math.max(1, Math.floor(size));
  let workers = [];
  let nextId = 1;

  function start() {
    if (workers.length) return;
    workers = Array.from({ length: size }, () => ({ w: spawn(), busy: false }));
  }

  /** Runs one call on worker `slot`; resolves with its result. */
  function run(slot, fn, args) {
    return new Promise((resolve, reject) => {
      const id = nextId++;
      slot.busy = true;
      slot.w.onmessage = (e) => {
        const data = e.data ?? e; // worker_threads passes the data itself
        if (data.id !== id) return;
        slot.busy = false;
        if ('error' in data) reject(new Error(data.error));
        else resolve(data.result);
      };
      slot.w.onerror = (e) => {
        slot.busy = false;
        reject(new Error(`pool worker failed: ${e.message || e}`));
      };
      slot.w.postMessage({ id, fn, args });
    });
  }

  /**
   * Calls `fn(...argsList[i])` for every i across the workers; resolves with
   * the results in argsList order. `onProgress(done, total)` after each call;
   * aborting `signal` terminates the workers (new ones start on the next map)
   * and rejects with an AbortError.
   */
  function map(fn, argsList, /** @type {MapOptions} */ { onProgress, signal } = {}) {
    start();
    const results = new Array(argsList.length);
    let next = 0;
    let done = 0;
    return new Promise((resolve, reject) => {
      let failed = false;
      const fail = (e) => {
        if (failed) return;
        failed = true;
        signal?.removeEventListener('abort', onAbort);
        reject(e);
      };
      const onAbort = () => {
        terminate();
        fail(Object.assign(new Error('cancelled'), { name: 'AbortError' }));
      };
      if (signal?.aborted) return onAbort();
      signal?.addEventListener('abort', onAbort, { once: true });
      if (!argsList.length) return resolve(results);
      const feed = (slot) => {
        if (failed || next >= argsList.length) return;
        const i = next++;
        run(slot, fn, argsList[i]).then(
          (r) => {
            if (failed) return;
            results[i] = r;
            done++;
            onProgress?.(done, argsList.length);
            if (done === argsList.length) {
              signal?.removeEventListener('abort', onAbort);
              resolve(results);
            } else feed(slot);
          },
          (e) => fail(e),
        );
      };
      for (const slot of workers) feed(slot);
    });
  }

  function terminate() {
    for (const { w } of workers) w.terminate();
    workers = [];
  }

  return { size, map, close: terminate };
}

/** Splits `list` into `n` contiguous chunks of near-equal length (none empty). */
export function chunks(list, n) {
  const k = Math.max(1, Math.min(n, list.length));
  return Array.from({ length: k }, (_, i) => list.slice(Math.floor((i * list.length) / k), Math.floor(((i + 1) * list.length) / k)));
}

/** The paper's K_FFP sweep: one `bestKffp` per condition (suzuki-best-kffp Figs. 14, 15, 20, 22). */
export function kffpSweep(pool, machine, conditions, options = {}) {
  return pool.map('bestKffp', conditions.map((c) => [machine, c]), options);
}

/** `travelRangeSweep` with its `ranges` split into chunks, concatenated in order. */
export async function travelRangeSweep(pool, config, options = {}) {
  const parts = chunks(config.ranges, pool.size * 4);
  return (await pool.map('travelRangeSweep', parts.map((ranges) => [{ ...config, ranges }]), options)).flat();
}

/** `angleSweep` with its `ranges` split into chunks, concatenated in order. */
export async function angleSweep(pool, config, options = {}) {
  const parts = chunks(config.ranges, pool.size * 4);
  return (await pool.map('angleSweep', parts.map((ranges) => [{ ...config, ranges }]), options)).flat();
}

/**
 * Monte-Carlo of the S-shape compensation (thasana §II-D): one
 * `compensateNc5` per seed in `seeds`, each drawing its own random machine.
 */
export function monteCarloNc5(pool, text, options, seeds, mapOptions = {}) {
  return pool.map('compensateNc5', seeds.map((seed) => [text, { ...options, monteCarlo: { ...options.monteCarlo, seed } }]), mapOptions);
}

let shared;
/**
 * The page's shared pool, created on first use; null where module workers
 * cannot start from a file (the single-file page opened from file://).
 */
export function sharedPool() {
  if (typeof Worker === 'undefined' || globalThis.location?.protocol === 'file:') return null;
  shared ??= createPool();
  return shared;
}

/**
 * `fn(...args)` for every entry of `argsList` on the shared pool, or one by
 * one through `api` (the page's single worker) where there is no pool.
 * Results in argsList order; `onProgress(done, total)` after each call.
 */
export async function mapCalls(api, fn, argsList, /** @type {MapOptions} */ { onProgress, signal } = {}) {
  const pool = sharedPool();
  if (pool) return pool.map(fn, argsList, { onProgress, signal });
  const out = [];
  for (const args of argsList) {
    if (signal?.aborted) throw Object.assign(new Error('cancelled'), { name: 'AbortError' });
    out.push(await api.call(fn, args));
    onProgress?.(out.length, argsList.length);
  }
  return out;
}
