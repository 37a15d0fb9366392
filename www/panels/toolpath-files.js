// Several program files for the tool-path panel: the dropped files are split
// into the main program, chosen by the core (ncMainFile: the first that ends
// with M2/M30, else the first that is no subprogram), and the extra files
// that hold the subprograms it calls (M98, G65, o<name> call). checkNc and
// simulateToolPath receive them as `files`; errors in them name the file.
import { h } from '../lib/ui.js';

/** State of the extra files: take(list) on a drop, options(o) adds `files`. */
export function programFiles(api, { onMain, onMainFile, onRefused }) {
  let extra = [];
  const note = h('div', { id: 'toolpath-files', style: 'font-size:90%' });
  const clear = () => {
    extra = [];
    note.replaceChildren();
  };
  async function take(list) {
    // a file too large to read whole comes unread ({ name, file }): it is
    // read in chunks as the main program alone
    const large = list.find((f) => f.file);
    if (large && list.length > 1) {
      return onRefused(new Error(`${large.name} is too large to read with other files: drop it alone (a large program is read in chunks as the main program alone; paste its subprograms after M30 in it)`));
    }
    if (list.length === 1) {
      clear();
      return large ? onMainFile(large.file, large.name) : onMain(list[0].text, list[0].name);
    }
    const i = await api.call('ncMainFile', [list.map((f) => f.text)]);
    const main = list[i];
    extra = list.filter((_, k) => k !== i).map(({ name, text }) => ({ name, text }));
    note.replaceChildren(
      h('span', { id: 'toolpath-files-main' }, `Main program: ${main.name}`),
      ` (the one that ends with M2/M30); subprogram files: ${extra.map((f) => f.name).join(', ')}. `,
      h('button', { onclick: () => { clear(); onMain(main.text, main.name); } }, 'Forget them'),
    );
    return onMain(main.text, main.name);
  }
  return {
    note,
    take,
    clear,
    /** `o` with the extra files added (undefined stays undefined when there are none). */
    options: (o) => (extra.length ? { ...(o || {}), files: extra } : o),
  };
}
