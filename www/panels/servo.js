// Servo & Best K_FFP panel (shell): shows the nmv5000 preset from the core.
import { h, table, fmt } from '../lib/ui.js';

export async function mount(root, api) {
  const m = await api.call('machinePreset', ['nmv5000']);
  const axes = Object.keys(m.axes);
  const fields = ['kind', 'j', 'j1', 'c', 'kpp', 'kvp', 'kvi', 'kffp', 'ts', 'ta', 'tp', 'torqueMax', 'lead'];
  root.replaceChildren(
    h('div', { class: 'card' }, h('h3', {}, `Preset ${m.name}`), h('p', {}, m.description), h('p', { class: 'lead' }, `Source: ${m.source}`),
      table(['field', ...axes.map((a) => a.toUpperCase())], fields.map((f) => [f, ...axes.map((a) => (typeof m.axes[a][f] === 'number' ? fmt(m.axes[a][f], 4) : m.axes[a][f] ?? '—'))]))),
  );
  root.querySelector('table').id = 'servo-preset-table';
}
