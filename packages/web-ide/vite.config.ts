import { defineConfig } from 'vite';
import { fileURLToPath } from 'node:url';

const monacoEsm = fileURLToPath(new URL('../../node_modules/monaco-editor/esm/vs/', import.meta.url));

// The production build is served by server/ide-server.ts; `npm run dev` proxies /api to it.
export default defineConfig({
  base: './',
  // monaco-editor's package exports append `.js` to every subpath: reach its CSS files directly.
  resolve: { alias: [{ find: /^monaco-css\/(.*)$/, replacement: `${monacoEsm}$1` }] },
  build: {
    outDir: 'dist',
    emptyOutDir: true,
    sourcemap: false,
    chunkSizeWarningLimit: 4000,
    target: 'es2022',
  },
  worker: { format: 'es' },
  server: { proxy: { '/api': 'http://127.0.0.1:7400' } },
});
