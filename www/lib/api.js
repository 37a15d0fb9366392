// The page's one door to the wasm core. Calls run in a Web Worker so that long
// sweeps never freeze the page; where no worker can be created (e.g. a page
// opened from file:// whose browser refuses blob workers), the same calls run
// in-page with the same interface.

/**
 * Starts a worker at `url` and resolves to the API once the worker reports
 * ready. `initMessage`, when given, is posted first (the single-file page
 * sends the wasm bytes this way).
 */
export function workerApi(url, { initMessage, timeoutMs = 30_000, type = 'module' } = {}) {
  return new Promise((resolve, reject) => {
    let worker;
    try {
      worker = new Worker(url, { type });
    } catch (e) {
      reject(e);
      return;
    }
    const pending = new Map();
    let next = 1;
    const timer = setTimeout(() => reject(new Error('the calculation worker did not start in time')), timeoutMs);
    worker.onerror = (e) => {
      e.preventDefault?.();
      clearTimeout(timer);
      reject(new Error(`the calculation worker failed to start: ${e.message || 'unknown error'}`));
    };
    worker.onmessage = ({ data }) => {
      if ('ready' in data) {
        clearTimeout(timer);
        resolve({
          version: data.ready,
          mode: 'worker',
          call(fn, args = [], { onProgress } = {}) {
            const id = next++;
            return new Promise((res, rej) => {
              pending.set(id, { res, rej, onProgress });
              worker.postMessage({ id, fn, args, progress: Boolean(onProgress) });
            });
          },
        });
        return;
      }
      if ('initError' in data) {
        clearTimeout(timer);
        reject(new Error(`the WebAssembly core failed to load: ${data.initError}`));
        return;
      }
      const p = pending.get(data.id);
      if (!p) return;
      if ('progress' in data) {
        p.onProgress?.(...data.progress);
        return;
      }
      pending.delete(data.id);
      if ('error' in data) p.rej(new Error(data.error));
      else p.res(data.result);
    };
    if (initMessage) worker.postMessage(initMessage);
  });
}

/** Same interface over an already-initialised wasm module namespace. */
export function inPageApi(wasm) {
  return {
    version: wasm.version(),
    mode: 'in-page',
    async call(fn, args = [], { onProgress } = {}) {
      const f = wasm[fn];
      if (typeof f !== 'function' || fn === 'default' || fn.startsWith('init')) throw new Error(`unknown function '${fn}'`);
      // Yield once so the page can paint the "running" state first.
      await new Promise((r) => setTimeout(r, 0));
      return onProgress ? f(...args, onProgress) : f(...args);
    },
  };
}
