// The NC program editor: CodeMirror 6 (virtualised: only the lines in view
// are in the DOM, so a 1 M-line program opens), with line numbers, G-code
// colouring, and the core's checkNc errors and warnings as lint marks at
// their line. Drawing only: the marks come from the core.
//
// The editor keeps the element id the page and its tests know: a textarea
// (`id`) that is a handle on the editor, not a second copy of the text.
// Its `value`, `selectionStart` and `selectionEnd` read and write the
// editor (and its own text mirrors the editor's up to MIRROR_MAX
// characters, for tools that read a textarea from outside the page's
// scripts, such as Playwright's inputValue; a megabyte in a textarea is
// what froze the page, so a larger program is not mirrored); an edit in the editor fires `input` on it (and `change` when the
// editor loses focus), as a textarea would; text typed or filled into the
// textarea itself goes to the editor. So boot.js's shared links and the
// run-state marks keep working unchanged.
import {
  EditorState, Text, EditorView, StateEffect, StateField, Decoration, lineNumbers, highlightActiveLine, highlightActiveLineGutter,
  keymap, drawSelection, StreamLanguage, HighlightStyle, syntaxHighlighting, lintGutter, setDiagnostics,
  defaultKeymap, history, historyKeymap, tags,
} from '../vendor/codemirror.js';

/** Longest text the handle's own value mirrors (characters). */
const MIRROR_MAX = 200_000;
/** A text longer than this (characters) is split into lines in slices. */
const SPLIT_IN_SLICES = 1_000_000;

/** G-code words, as a StreamLanguage (RS274/NGC, Fanuc and macro B). */
const gcode = StreamLanguage.define({
  name: 'gcode',
  startState: () => ({ comment: false }),
  token(stream, state) {
    if (state.comment) {
      if (stream.skipTo(')')) {
        stream.next();
        state.comment = false;
      } else stream.skipToEnd();
      return 'comment';
    }
    if (stream.eatSpace()) return null;
    const ch = stream.peek();
    if (ch === '(') {
      stream.next();
      state.comment = true;
      return 'comment';
    }
    if (ch === ';') {
      stream.skipToEnd();
      return 'comment';
    }
    if (ch === '%') {
      stream.next();
      return 'meta';
    }
    if (ch === '/' && stream.column() === stream.indentation()) {
      stream.next();
      return 'meta';
    }
    // Macro variables: #1, #<name>, ##1.
    if (stream.match(/^#+(\d+|<[^>]*>)/)) return 'variableName';
    if (stream.match(/^[Nn]\d+/)) return 'labelName';
    if (stream.match(/^[Oo](\d+|<[^>]*>)/)) return 'labelName';
    if (stream.match(/^[Gg]\s*\d+(\.\d+)?/)) return 'keyword';
    if (stream.match(/^[Mm]\s*\d+/)) return 'controlKeyword';
    if (stream.match(/^(IF|THEN|GOTO|WHILE|DO|END|EQ|NE|GT|GE|LT|LE|AND|OR|XOR|MOD|SIN|COS|TAN|ATAN|SQRT|ABS|ROUND|FIX|FUP|SUB|ENDSUB|CALL|RETURN|ELSE|ENDIF|ENDWHILE)\b/i)) return 'operatorKeyword';
    if (stream.match(/^[XYZABCUVWIJKR]/i)) return 'propertyName';
    if (stream.match(/^[FSTDHPQLE]/i)) return 'attributeName';
    if (stream.match(/^[+-]?(\d+\.?\d*|\.\d+)/)) return 'number';
    if (stream.match(/^[[\]=*/+-]/)) return 'operator';
    stream.next();
    return null;
  },
  tokenTable: {},
});

const colours = HighlightStyle.define([
  { tag: tags.comment, color: '#6a737d', fontStyle: 'italic' },
  { tag: tags.keyword, color: '#0b6bcb', fontWeight: '600' },
  { tag: tags.controlKeyword, color: '#8a3ffc', fontWeight: '600' },
  { tag: tags.propertyName, color: '#b3261e' },
  { tag: tags.attributeName, color: '#1b7f3b' },
  { tag: tags.number, color: '#1d232b' },
  { tag: tags.variableName, color: '#a85d00', fontWeight: '600' },
  { tag: tags.labelName, color: '#5b6673' },
  { tag: tags.operatorKeyword, color: '#a85d00' },
  { tag: tags.meta, color: '#5b6673' },
]);

/** The line highlighted from outside (the path view's pick). */
/** @type {import("@codemirror/state").StateEffectType<number>} */
const setMarked = StateEffect.define();
const markedLine = StateField.define({
  create: () => Decoration.none,
  update(deco, tr) {
    deco = deco.map(tr.changes);
    for (const e of tr.effects) {
      if (!e.is(setMarked)) continue;
      const n = e.value;
      deco = n >= 1 && n <= tr.state.doc.lines ? Decoration.set([Decoration.line({ class: 'cm-marked-line' }).range(tr.state.doc.line(n).from)]) : Decoration.none;
    }
    return deco;
  },
  provide: (f) => EditorView.decorations.from(f),
});

const theme = EditorView.theme({
  '&': { height: '330px', border: '1px solid var(--line)', borderRadius: '4px', fontSize: '13px', background: '#fff' },
  '.cm-scroller': { fontFamily: 'ui-monospace, "SFMono-Regular", Menlo, monospace', overflow: 'auto' },
  '.cm-marked-line': { background: '#fff3bf' },
  '&.cm-focused': { outline: '2px solid var(--accent-soft)' },
});

/**
 * The NC program editor.
 * @param {{ id: string, onLine?: (line: number) => void }} options
 *   id: the id of its textarea handle; onLine: the user put the cursor on
 *   a line (click or keys), 1-based.
 */
export function ncEditor({ id, onLine }) {
  const el = document.createElement('div');
  el.className = 'nc-editor';
  el.style.position = 'relative';
  // The handle: a 1 px, transparent textarea (Playwright's fill and
  // assistive tools see a textarea; people see the editor).
  const handle = document.createElement('textarea');
  handle.id = id;
  handle.spellcheck = false;
  handle.tabIndex = -1;
  handle.setAttribute('aria-hidden', 'true');
  handle.style.cssText = 'position:absolute;left:0;top:0;width:1px;height:1px;min-height:0;padding:0;border:0;opacity:0;resize:none;overflow:hidden;z-index:-1';
  const native = Object.getOwnPropertyDescriptor(HTMLTextAreaElement.prototype, 'value');

  let editedSinceChange = false;
  /** The next text set is shown read-only (setReadOnly). */
  let readOnly = false;
  const extensions = [
    lineNumbers(), highlightActiveLineGutter(), highlightActiveLine(), drawSelection(), history(),
    keymap.of([...defaultKeymap, ...historyKeymap]),
    gcode, syntaxHighlighting(colours), lintGutter(), markedLine, theme,
    EditorView.contentAttributes.of({ 'aria-label': 'NC program', spellcheck: 'false' }),
    EditorView.updateListener.of((u) => {
      if (u.docChanged) mirror();
      if (u.docChanged) {
        editedSinceChange = true;
        handle.dispatchEvent(new Event('input', { bubbles: true }));
      }
      const user = u.transactions.some((tr) => tr.isUserEvent('select') || tr.isUserEvent('input') || tr.isUserEvent('delete'));
      if (u.selectionSet && user && onLine) onLine(u.state.doc.lineAt(u.state.selection.main.head).number);
    }),
    EditorView.domEventHandlers({
      blur: () => {
        if (editedSinceChange) {
          editedSinceChange = false;
          handle.dispatchEvent(new Event('change', { bubbles: true }));
        }
      },
    }),
  ];
  const view = new EditorView({ parent: el, state: EditorState.create({ doc: '', extensions }) });
  el.prepend(handle);

  // The text as one string, made once per document version.
  let cachedDoc = null;
  let cachedText = '';
  /** A large text being split into lines (it is the value meanwhile). */
  let pending = null;
  let installs = 0;
  const text = () => {
    if (pending !== null) return pending;
    if (cachedDoc !== view.state.doc) {
      cachedDoc = view.state.doc;
      cachedText = cachedDoc.toString();
    }
    return cachedText;
  };
  /** Replaces the whole text (no input event, as a textarea's value
   * setter): a new editor state (no undo into the previous program, no
   * marks of it), cheaper than an edit of the whole text. */
  const install = (doc, str) => {
    view.setState(EditorState.create({ doc, extensions: readOnly ? [...extensions, EditorState.readOnly.of(true), EditorView.editable.of(false)] : extensions }));
    cachedDoc = view.state.doc;
    cachedText = str;
    mirror();
    view.scrollDOM.scrollTop = 0;
  };
  // Line ends as a textarea's value has them.
  const setText = (v) => {
    const str = String(v).replace(/\r\n?/g, '\n');
    const my = ++installs;
    if (str.length <= SPLIT_IN_SLICES) {
      pending = null;
      install(str, str);
      return;
    }
    // A large text is split into lines in slices of 25 ms (1 M lines in
    // one go, with its garbage collection, held the page for ~0.6 s).
    pending = str;
    (async () => {
      const lines = [];
      let t0 = performance.now();
      for (let at = 0; ;) {
        const nl = str.indexOf('\n', at);
        lines.push(str.slice(at, nl < 0 ? str.length : nl));
        if (nl < 0) break;
        at = nl + 1;
        if (!(lines.length & 8191) && performance.now() - t0 > 25) {
          await new Promise((r) => setTimeout(r, 0));
          if (my !== installs) return;
          t0 = performance.now();
        }
      }
      if (my !== installs) return;
      pending = null;
      install(Text.of(lines), str);
    })();
  };
  let mirrored = '';
  function mirror() {
    const t = view.state.doc.length <= MIRROR_MAX ? text() : '';
    if (t !== mirrored) native.set.call(handle, (mirrored = t));
  }
  Object.defineProperty(handle, 'value', { get: text, set: setText });
  Object.defineProperty(handle, 'selectionStart', { get: () => view.state.selection.main.from });
  Object.defineProperty(handle, 'selectionEnd', { get: () => view.state.selection.main.to });
  // Text typed or filled into the handle goes to the editor (as an edit,
  // so listeners of `input` see it).
  handle.addEventListener('input', (e) => {
    const typed = native.get.call(handle);
    if (typed === mirrored) return;
    e.stopImmediatePropagation();
    view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: typed }, selection: { anchor: 0 } });
  });

  /** Scrolls the editor (only the editor, not the page) so that the line at `pos` is in its middle. */
  function centre(pos) {
    const s = view.scrollDOM;
    s.scrollTop = Math.max(0, view.lineBlockAt(pos).top - s.clientHeight / 2);
  }

  /** Selects line `n` (1-based) and scrolls the editor to it; `focus`: and
   * focuses it (the page itself does not scroll: a click in the path view
   * below keeps the view where it is). */
  function selectLine(n, { focus = true } = {}) {
    const doc = view.state.doc;
    if (!(n >= 1 && n <= doc.lines)) return;
    const line = doc.line(n);
    view.dispatch({ selection: { anchor: line.from, head: line.to } });
    centre(line.from);
    if (focus) view.contentDOM.focus({ preventScroll: true });
  }

  /**
   * The core's check (checkNc) as marks at their lines: errors and warnings
   * of the main program (a subprogram file's are listed beside, not here).
   * @param {import('../pkg/mtmotion.js').NcCheck | null} check
   */
  let pendingCheck = null;
  let checkTimer = 0;
  function showCheck(check) {
    // Applied in a task of its own: after a new program is set, the editor's
    // first layout and these marks would otherwise make one long task.
    pendingCheck = check;
    clearTimeout(checkTimer);
    checkTimer = setTimeout(() => applyCheck(pendingCheck));
  }
  function applyCheck(check) {
    if (pending !== null) {
      checkTimer = setTimeout(() => applyCheck(pendingCheck), 50);
      return;
    }
    const doc = view.state.doc;
    const at = (w, severity) => {
      const n = Math.min(Math.max(w.line, 1), doc.lines);
      const line = doc.line(n);
      const from = Math.min(line.from + Math.max(w.column - 1, 0), line.to);
      return { from, to: Math.max(from, line.to), severity, message: w.message };
    };
    const own = (w) => !w.file;
    const marks = check ? [...check.errors.filter(own).map((w) => at(w, 'error')), ...check.warnings.filter(own).map((w) => at(w, 'warning'))] : [];
    view.dispatch(setDiagnostics(view.state, marks));
  }

  /** Marks line `n` (0: none) without moving the cursor or the focus. */
  function markLine(n) {
    view.dispatch({ effects: setMarked.of(n) });
    if (n >= 1 && n <= view.state.doc.lines) centre(view.state.doc.line(n).from);
  }

  /** Texts set from now on are read-only (true) or editable (false). */
  const setReadOnly = (on) => {
    readOnly = on;
  };
  return { el, handle, view, selectLine, showCheck, markLine, setReadOnly };
}
