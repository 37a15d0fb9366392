// ESLint over the page (www/): the recommended rules, a few that catch real
// mistakes (unused names, == against non-null, shadowed names, a `let` read
// before its declaration in the same scope), and the house format as
// @stylistic rules (2-space indent, single quotes, semicolons, trailing
// commas on multi-line literals, 1TBS braces, spacing). The format rules
// state the style the page is written in rather than reflowing it the way
// prettier would (which rewrote about 1,200 of the 2,700 lines).
// `npx eslint --fix www` applies the format rules.
import js from '@eslint/js';
import stylistic from '@stylistic/eslint-plugin';
import globals from 'globals';

export default [
  { ignores: ['node_modules/', 'target/', 'pkg/', 'pkg-embed/', 'dist/'] },
  js.configs.recommended,
  {
    files: ['www/**/*.js'],
    languageOptions: {
      ecmaVersion: 2024,
      sourceType: 'module',
      globals: { ...globals.browser, ...globals.worker },
    },
    plugins: { '@stylistic': stylistic },
    rules: {
      'no-unused-vars': ['error', { args: 'after-used', argsIgnorePattern: '^_', caughtErrors: 'none' }],
      eqeqeq: ['error', 'always', { null: 'ignore' }],
      'no-var': 'error',
      'prefer-const': 'error',
      'no-shadow': 'error',
      // Closures may name a `const` declared further down (event handlers
      // wired before the elements they touch); a read in the same scope
      // before the declaration is a real error.
      'no-use-before-define': ['error', { functions: false, classes: true, variables: false }],
      'no-console': ['error', { allow: ['warn', 'error'] }],

      '@stylistic/indent': ['error', 2, { SwitchCase: 1, flatTernaryExpressions: true, offsetTernaryExpressions: true, ignoredNodes: ['CallExpression > ArrowFunctionExpression'] }],
      '@stylistic/quotes': ['error', 'single', { avoidEscape: true, allowTemplateLiterals: 'always' }],
      '@stylistic/semi': ['error', 'always'],
      '@stylistic/comma-dangle': ['error', 'always-multiline'],
      '@stylistic/brace-style': ['error', '1tbs', { allowSingleLine: true }],
      '@stylistic/arrow-parens': ['error', 'always'],
      '@stylistic/arrow-spacing': 'error',
      '@stylistic/comma-spacing': 'error',
      '@stylistic/key-spacing': 'error',
      '@stylistic/keyword-spacing': 'error',
      '@stylistic/space-before-blocks': 'error',
      '@stylistic/space-infix-ops': 'error',
      '@stylistic/space-in-parens': 'error',
      '@stylistic/object-curly-spacing': ['error', 'always'],
      '@stylistic/array-bracket-spacing': 'error',
      '@stylistic/block-spacing': 'error',
      '@stylistic/no-trailing-spaces': 'error',
      '@stylistic/no-multi-spaces': ['error', { ignoreEOLComments: true }],
      '@stylistic/no-multiple-empty-lines': ['error', { max: 1 }],
      '@stylistic/eol-last': 'error',
      '@stylistic/no-tabs': 'error',
      '@stylistic/semi-spacing': 'error',
      '@stylistic/function-call-spacing': 'error',
      '@stylistic/space-before-function-paren': ['error', { anonymous: 'always', named: 'never', asyncArrow: 'always' }],
      '@stylistic/quote-props': ['error', 'as-needed'],
      '@stylistic/new-parens': 'error',
    },
  },
];
