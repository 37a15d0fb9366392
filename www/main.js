// Entry of the served page: the core runs in a module worker (worker.js).
import { boot } from './lib/boot.js';
import { workerApi } from './lib/api.js';

boot({
  makeApi: () => workerApi(new URL('./worker.js', import.meta.url)),
  loadPanel: (name) => import(`./panels/${name}.js`),
});
