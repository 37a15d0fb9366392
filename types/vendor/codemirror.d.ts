// The page imports CodeMirror 6 from vendor/codemirror.js (bundled by
// scripts/vendor.mjs from scripts/vendor/codemirror.mjs); its types are the
// npm packages' own.
export { EditorState, StateField, StateEffect, RangeSetBuilder, Text } from '@codemirror/state';
export { EditorView, Decoration, lineNumbers, highlightActiveLine, highlightActiveLineGutter, keymap, drawSelection } from '@codemirror/view';
export { StreamLanguage, HighlightStyle, syntaxHighlighting } from '@codemirror/language';
export { linter, lintGutter, setDiagnostics, forceLinting } from '@codemirror/lint';
export { defaultKeymap, history, historyKeymap } from '@codemirror/commands';
export { tags } from '@lezer/highlight';
