// Loads the npm packages pinned in tests/npm/package.json from the folder tests/npm/install.sh
// installed them in (outside the repository): A3_NPM_DIR, the parent of that node_modules.
// ES imports of bare names resolve from the importing file's folder, so tests load the SDKs
// through a require rooted in that folder instead.
import { createRequire } from 'node:module';
import path from 'node:path';

export function requireSdk(name) {
  const dir = process.env.A3_NPM_DIR;
  if (!dir) throw new Error('A3_NPM_DIR is not set: run this test through tests/npm/run_node_test.sh (ctest -L npm)');
  return createRequire(path.join(dir, 'package.json'))(name);
}
