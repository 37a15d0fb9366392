// toolpath panel (shell): the capability lands with its issue.
import { h } from '../lib/ui.js';

export async function mount(root) {
  root.replaceChildren(h('p', { class: 'warn-box' }, 'This capability is being built; the description above says what it will do.'));
}
