// The shared NC corpus of real public programs (not in the repository:
// they are other people's files, see its SOURCES.md): `../shared/nc_corpus`
// from the project root, or the folder named by MTMOTION_NC_CORPUS. The
// same lookup as tests/support/corpus.rs. Without it, a test that needs it
// says it was skipped and why.
import { existsSync, readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { join } from 'node:path';

const root = fileURLToPath(new URL('../../', import.meta.url));

/** The corpus folder, or null. */
export const corpusDir = (() => {
  const d = process.env.MTMOTION_NC_CORPUS || join(root, '..', 'shared', 'nc_corpus');
  return existsSync(d) ? d : null;
})();

/** Why the corpus is missing (for a skip message). */
export const corpusMissing = corpusDir
  ? ''
  : `the NC corpus folder ${process.env.MTMOTION_NC_CORPUS || join(root, '..', 'shared', 'nc_corpus')} is not there (set MTMOTION_NC_CORPUS to the shared corpus)`;

/** The text of corpus file `name`, or null when the corpus is missing. */
export function readCorpus(name) {
  return corpusDir ? readFileSync(join(corpusDir, name), 'utf8') : null;
}
