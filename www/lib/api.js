// The page's one door to the wasm core. Calls run in a Web Worker so that long
// sweeps never freeze the page; where no worker can be created (e.g. a page
// opened from file:// whose browser refuses blob workers), the same calls run
// in-page with the same interface.
//
// Every worker call has a time limit and can be cancelled. Both end the
// worker (a running wasm call cannot be interrupted otherwise) and start a
// fresh one; so does a trap inside the wasm instance, which may leave it
// unusable. Calls queued behind the one that ended are sent to the new
// worker; only that one call fails, with a message in words.

import { derived } from './derived.js';

/**
 * Options of one call: `onProgress(fraction, message)` for the functions
 * that report progress, `signal` cancels, `timeoutMs` limits the time.
 * @typedef {{ onProgress?: (fraction: number, message: string) => void, signal?: AbortSignal, timeoutMs?: number }} CallOptions
 */

/** @typedef {typeof import('../pkg/mtmotion.js')} Wasm the wasm module's exports (pkg/mtmotion.d.ts) */
/** @typedef {typeof import('./derived.js').derived} Derived */
/**
 * The core's exports and the page's derived calls (lib/derived.js, their
 * first argument, the module, supplied where they run).
 * @typedef {Wasm & { [K in keyof Derived]: Derived[K] extends (wasm: any, ...args: infer A) => infer R ? (...args: A) => R : never }} Core
 */
/**
 * The name of a core function the page may call (not the module's own
 * initialisers).
 * @typedef {Exclude<{ [K in keyof Core]: Core[K] extends (...args: any[]) => any ? K : never }[keyof Core], 'default' | 'initSync' | 'start'>} CoreFunction
 */
/**
 * A typed call: `api.call('fitCircle', [x, y])` checks the arguments
 * against the core's `.d.ts` and resolves to its result type.
 * @typedef {<K extends CoreFunction>(fn: K, args?: Parameters<Core[K]>, options?: CallOptions) => Promise<ReturnType<Core[K]>>} CoreCall
 */

/**
 * The page's handle on the core (the same shape in a worker and in-page).
 * @typedef {object} Api
 * @property {string} version the core's version
 * @property {'worker' | 'in-page'} mode where the calls run
 * @property {number} restarts workers replaced so far
 * @property {CoreCall} call
 */

/** Default time limit of one call, ms. */
export const CALL_TIMEOUT_MS = 60_000;

function trapMessage(detail) {
  return `the calculation failed inside the engine (${detail}); the engine was restarted, so the page keeps working — change the inputs and run again`;
}

/** Starts a worker and resolves once it reports ready (or rejects). */
function startWorker(url, { initMessage, timeoutMs, type }) {
  return new Promise((resolve, reject) => {
    let worker;
    try {
      worker = new Worker(url, { type });
    } catch (e) {
      reject(e);
      return;
    }
    const timer = setTimeout(() => {
      worker.terminate();
      reject(new Error('the calculation worker did not start in time'));
    }, timeoutMs);
    worker.onerror = (e) => {
      e.preventDefault?.();
      clearTimeout(timer);
      worker.terminate();
      reject(new Error(`the calculation worker failed to start: ${e.message || 'unknown error'}`));
    };
    worker.onmessage = ({ data }) => {
      clearTimeout(timer);
      if ('ready' in data) resolve({ worker, version: data.ready });
      else if ('initError' in data) {
        worker.terminate();
        reject(new Error(`the WebAssembly core failed to load: ${data.initError}`));
      }
    };
    if (initMessage) worker.postMessage(initMessage);
  });
}

/**
 * Starts a worker at `url` and resolves to the API once the worker reports
 * ready. `initMessage`, when given, is posted first (the single-file page
 * sends the wasm bytes this way).
 *
 * `api.call(fn, args, { onProgress, signal, timeoutMs })`: `signal` (an
 * AbortSignal) cancels the call; `timeoutMs` (default CALL_TIMEOUT_MS)
 * stops it. `api.restarts` counts the workers replaced so far.
 *
 * @param {string | URL} url
 * @param {{ initMessage?: unknown, timeoutMs?: number, type?: WorkerType }} [options]
 * @returns {Promise<Api>}
 */
export async function workerApi(url, { initMessage, timeoutMs = 30_000, type = 'module' } = {}) {
  const opts = { initMessage, timeoutMs, type };
  const started = await startWorker(url, opts);
  let worker = started.worker;
  const version = started.version;
  const pending = new Map(); // id → { msg, res, rej, onProgress, timer }, in send order
  let next = 1;
  let restarting = null;
  /** @type {Api} */
  const api = { version, mode: 'worker', restarts: 0, call: undefined };

  const finish = (id) => {
    const p = pending.get(id);
    if (!p) return null;
    clearTimeout(p.timer);
    p.signal?.removeEventListener('abort', p.onAbort);
    pending.delete(id);
    return p;
  };

  const attach = (w) => {
    w.onmessage = ({ data }) => {
      const p = pending.get(data.id);
      if (!p) return;
      if ('progress' in data) {
        p.onProgress?.(...data.progress);
        return;
      }
      finish(data.id);
      if ('error' in data) {
        p.rej(new Error(data.trap ? trapMessage(data.error) : data.error));
        if (data.trap) restart();
      } else p.res(data.result);
    };
    w.onerror = (e) => {
      e.preventDefault?.();
      // An uncaught failure in the worker: the running call fails, the rest go on.
      const first = pending.keys().next();
      if (!first.done) finish(first.value)?.rej(new Error(trapMessage(e.message || 'worker error')));
      restart();
    };
  };
  attach(worker);

  // Ends the current worker and starts a new one; the calls still pending
  // (queued behind the one that ended) are sent to it in order.
  function restart() {
    worker.terminate();
    api.restarts++;
    restarting = startWorker(url, opts).then(
      (w) => {
        worker = w.worker;
        attach(worker);
        restarting = null;
        for (const p of pending.values()) worker.postMessage(p.msg);
      },
      (e) => {
        restarting = null;
        for (const id of [...pending.keys()]) finish(id)?.rej(e);
      },
    );
  }

  /**
   * @param {string} fn
   * @param {unknown[]} [args]
   * @param {CallOptions} [options]
   * @returns {Promise<any>}
   */
  const send = (fn, args = [], { onProgress, signal, timeoutMs: limit = CALL_TIMEOUT_MS } = {}) => {
    const id = next++;
    return new Promise((res, rej) => {
      if (signal?.aborted) {
        rej(new Error('cancelled'));
        return;
      }
      const msg = { id, fn, args, progress: Boolean(onProgress) };
      // The running call is the first pending one: ending it ends the worker.
      const stop = (message) => {
        const running = pending.keys().next().value === id;
        const p = finish(id);
        if (!p) return;
        p.rej(new Error(message));
        if (running) restart();
      };
      const onAbort = () => stop('cancelled');
      const timer = setTimeout(
        () => stop(`the calculation took longer than ${Math.round(limit / 1000)} s and was stopped; reduce the work (a coarser time step, a shorter program or trace) and run again`),
        limit,
      );
      signal?.addEventListener('abort', onAbort, { once: true });
      pending.set(id, { msg, res, rej, onProgress, timer, signal, onAbort });
      if (!restarting) worker.postMessage(msg);
    });
  };
  api.call = /** @type {CoreCall} */ (send);
  return api;
}

/**
 * Same interface over an already-initialised wasm module namespace.
 * @returns {Api}
 */
export function inPageApi(wasm) {
  return {
    version: wasm.version(),
    mode: 'in-page',
    restarts: 0,
    call: /** @type {CoreCall} */ (callInPage),
  };

  /**
   * @param {string} fn
   * @param {unknown[]} [args]
   * @param {CallOptions} [options]
   */
  async function callInPage(fn, args = [], { onProgress, signal } = {}) {
    const f = Object.hasOwn(derived, fn) ? (...a) => derived[fn](wasm, ...a) : wasm[fn];
    if (typeof f !== 'function' || fn === 'default' || fn.startsWith('init')) throw new Error(`unknown function '${fn}'`);
    // Yield once so the page can paint the "running" state first.
    await new Promise((r) => setTimeout(r, 0));
    if (signal?.aborted) throw new Error('cancelled');
    try {
      return await (onProgress ? f(...args, onProgress) : f(...args));
    } catch (e) {
      if (e instanceof WebAssembly.RuntimeError) throw new Error(`the calculation failed inside the engine (${e.message}); reload the page to restart it`, { cause: e });
      throw e;
    }
  }
}
