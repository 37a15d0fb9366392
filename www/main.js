// Page start-up: load the core (in the worker), show the preset it returns,
// mount each capability panel, then mark the page ready for the tests.
import { createApi } from './lib/api.js';
import { showError } from './lib/ui.js';

const PANELS = ['servo', 'toolpath', 'ballbar', 'kinematics'];
const status = document.getElementById('status');

function selectTab(name) {
  for (const b of document.querySelectorAll('[data-tab]')) b.setAttribute('aria-selected', String(b.dataset.tab === name));
  for (const s of document.querySelectorAll('[data-panel]')) s.hidden = s.dataset.panel !== name;
  document.dispatchEvent(new CustomEvent('mtmotion:tab', { detail: name }));
}
for (const b of document.querySelectorAll('[data-tab]')) b.addEventListener('click', () => selectTab(b.dataset.tab));

async function start() {
  let api;
  try {
    api = await createApi();
    // Proves the round trip through the worker with a real core call.
    const preset = await api.call('machinePreset', ['nmv5000']);
    status.textContent = `Core v${api.version} ready (${api.mode}) · default machine: ${preset.name}`;
  } catch (e) {
    status.textContent = `The calculation core could not start: ${e.message}`;
    status.classList.add('error');
    console.error(e);
    return;
  }
  await Promise.all(
    PANELS.map(async (name) => {
      const body = document.querySelector(`#panel-${name} .panel-body`);
      try {
        const panel = await import(`./panels/${name}.js`);
        await panel.mount(body, api);
      } catch (e) {
        showError(body, e);
        console.error(`panel ${name}:`, e);
      }
    }),
  );
  document.body.dataset.ready = 'true';
}

start();
