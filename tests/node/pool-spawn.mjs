// A worker_threads stand-in for the Web Worker that www/lib/pool.js spawns.
import { Worker } from 'node:worker_threads';

export const nodeSpawn = () => {
  const w = new Worker(new URL('./fixtures/pool-worker.mjs', import.meta.url));
  return {
    postMessage: (m) => w.postMessage(m),
    terminate: () => w.terminate(),
    set onmessage(f) {
      w.removeAllListeners('message');
      w.on('message', (data) => f({ data }));
    },
    set onerror(f) {
      w.removeAllListeners('error');
      w.on('error', f);
    },
  };
};
