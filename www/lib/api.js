// The page's one door to the wasm core. Calls run in a Web Worker so that long
// sweeps never freeze the page; where no worker can be created (e.g. a page
// opened from file://), the same calls run in-page.

/** Creates the API; resolves once the core is loaded. */
export async function createApi({ workerUrl = new URL('../worker.js', import.meta.url), inPage } = {}) {
  try {
    return await workerApi(workerUrl);
  } catch (e) {
    if (!inPage) throw e;
    return inPageApi(await inPage());
  }
}

function workerApi(url) {
  return new Promise((resolve, reject) => {
    let worker;
    try {
      worker = new Worker(url, { type: 'module' });
    } catch (e) {
      reject(e);
      return;
    }
    const pending = new Map();
    let next = 1;
    worker.onerror = (e) => reject(new Error(`worker failed to start: ${e.message || 'unknown error'}`));
    worker.onmessage = ({ data }) => {
      if ('ready' in data) {
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
  });
}

/** Same interface over an already-initialised wasm module namespace. */
export function inPageApi(wasm) {
  return {
    version: wasm.version(),
    mode: 'in-page',
    async call(fn, args = [], { onProgress } = {}) {
      const f = wasm[fn];
      if (typeof f !== 'function') throw new Error(`unknown function '${fn}'`);
      // Yield once so the page can paint the "running" state first.
      await new Promise((r) => setTimeout(r, 0));
      return onProgress ? f(...args, onProgress) : f(...args);
    },
  };
}
