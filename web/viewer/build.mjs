// Bundles the viewer: OUTDIR/viewer.js (one IIFE, CSS inlined as text) and OUTDIR/index.html
// (the template the server fills). Usage: node build.mjs [OUTDIR], OUTDIR defaults to dist.
import { build } from 'esbuild';
import { existsSync, statSync } from 'node:fs';
import { copyFile, mkdir } from 'node:fs/promises';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const outdir = resolve(process.argv[2] ?? 'dist');

// Packages older than the lock file would bundle other versions than the ones pinned.
const lock = join(here, 'package-lock.json');
const installed = join(here, 'node_modules/.package-lock.json');
if (!existsSync(installed) || statSync(lock).mtimeMs > statSync(installed).mtimeMs) {
  console.error('build.mjs: the npm packages are missing or older than package-lock.json: '
    + 'run scripts/install-deps.sh (or `npm ci` in web/viewer)');
  process.exit(1);
}

try {
  await mkdir(outdir, { recursive: true });
  await build({
    entryPoints: [join(here, 'src/main.js')],
    outfile: join(outdir, 'viewer.js'),
    bundle: true,
    format: 'iife',
    minify: true,
    target: 'es2020',
    // Styles travel inside the bundle so one <script> is the whole page.
    loader: { '.css': 'text' },
    logLevel: 'warning',
  });
  await copyFile(join(here, 'src/index.html'), join(outdir, 'index.html'));
} catch (err) {
  console.error(`build.mjs: viewer build into ${outdir} failed: ${err.message ?? err}`);
  process.exit(1);
}
