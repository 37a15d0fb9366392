// Entry of dist/vendor/codemirror.js (scripts/vendor.mjs): the parts of
// CodeMirror 6 the NC program editor (www/lib/editor.js) uses, bundled
// once so the page imports one local file (no CDN, no bare specifiers).
export { EditorState, StateField, StateEffect, RangeSetBuilder, Text } from '@codemirror/state';
export { EditorView, Decoration, lineNumbers, highlightActiveLine, highlightActiveLineGutter, keymap, drawSelection } from '@codemirror/view';
export { StreamLanguage, HighlightStyle, syntaxHighlighting } from '@codemirror/language';
export { linter, lintGutter, setDiagnostics, forceLinting } from '@codemirror/lint';
export { defaultKeymap, history, historyKeymap } from '@codemirror/commands';
export { tags } from '@lezer/highlight';
