/**
 * Lazy, typed access to the sibling packages (language, codegen, build service). They are loaded
 * on first use so the file API and the editor keep working when one of them is not built; the
 * user then gets a clear error naming the missing package instead of a crash.
 */
import type { GenerateReport } from './api-types.js';
import type { RegionParser } from './region-guard.js';
import { HttpError } from './http-error.js';

export interface BuildServerLike {
  handle(req: import('node:http').IncomingMessage, res: import('node:http').ServerResponse): boolean | Promise<boolean>;
  handleUpgrade?(req: import('node:http').IncomingMessage, socket: import('node:stream').Duplex, head: Buffer): boolean;
  close(): Promise<void>;
}

async function importPackage<T>(name: string): Promise<T> {
  try {
    return (await import(name)) as T;
  } catch (e) {
    throw new HttpError(503, `${name} is not available (${(e as Error).message.split('\n')[0]}); run \`npm run build\` at the repository root`);
  }
}

export async function loadWorkspaceDocuments(dir: string): Promise<{ documents: unknown[]; diagnostics?: unknown }> {
  const lang = await importPackage<{ loadWorkspace(dir: string): Promise<{ documents: unknown[]; diagnostics?: unknown }> }>(
    '@contract-studio/language/node',
  );
  return lang.loadWorkspace(dir);
}

export async function runCodegen(documents: unknown[], outDir: string, options: Record<string, unknown>): Promise<GenerateReport> {
  const codegen = await importPackage<{
    generateArchitecture(documents: unknown[], outDir: string, options: Record<string, unknown>): Promise<GenerateReport> | GenerateReport;
  }>('@contract-studio/codegen');
  return codegen.generateArchitecture(documents, outDir, options);
}

/** codegen's protected-region parser (parseRegions + RegionSyntaxError), for the guard of generated files. */
export async function loadRegionParser(): Promise<RegionParser> {
  const codegen = await importPackage<Partial<RegionParser>>('@contract-studio/codegen');
  if (typeof codegen.parseRegions !== 'function' || typeof codegen.RegionSyntaxError !== 'function') {
    throw new HttpError(503, '@contract-studio/codegen does not export parseRegions/RegionSyntaxError; run `npm run build` at the repository root');
  }
  return { parseRegions: codegen.parseRegions, RegionSyntaxError: codegen.RegionSyntaxError };
}

export async function createEmbeddedBuildServer(workspaceRoot: string): Promise<BuildServerLike | string> {
  try {
    const name = '@contract-studio/build-service';
    const bs = (await import(name)) as {
      createBuildServer(options: Record<string, unknown>): BuildServerLike;
    };
    return bs.createBuildServer({ host: '127.0.0.1', port: 0, projectRoots: [workspaceRoot], basePath: '/api', concurrency: 1 });
  } catch (e) {
    return `build service unavailable: ${(e as Error).message.split('\n')[0]}`;
  }
}
