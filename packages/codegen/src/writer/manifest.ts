import { createHash } from 'node:crypto';
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { parseRegions } from '../regions/parse-regions.js';

/**
 * The manifest `<out>/.contract-manifest.json` lists the files the generator wrote last time and,
 * per protected region, a hash of the default content it generated. It tells which files belong
 * to deleted entities and whether a region still holds only the generator's default (no user code).
 */
export const MANIFEST_NAME = '.contract-manifest.json';

export interface Manifest {
    version: 1;
    /** path -> region ID -> hash of the generated default content */
    files: Record<string, Record<string, string>>;
}

export function hashContent(content: string): string {
    return createHash('sha1').update(content, 'latin1').digest('hex').slice(0, 16);
}

/** The default-content hashes of a freshly generated file (byte string). */
export function regionDefaults(generated: string, file: string): Record<string, string> {
    const defaults: Record<string, string> = {};
    for (const r of parseRegions(generated, file).regions) defaults[r.id] = hashContent(r.content);
    return defaults;
}

export type ManifestLoad = { manifest: Manifest } | { manifest: undefined; problem?: string };

export function loadManifest(outDir: string): ManifestLoad {
    const file = join(outDir, MANIFEST_NAME);
    if (!existsSync(file)) return { manifest: undefined };
    try {
        const data = JSON.parse(readFileSync(file, 'utf8')) as Manifest;
        if (data?.version !== 1 || typeof data.files !== 'object' || data.files === null) {
            return { manifest: undefined, problem: 'unknown manifest format, ignored' };
        }
        return { manifest: data };
    } catch (e) {
        return { manifest: undefined, problem: `unreadable manifest, ignored (${(e as Error).message})` };
    }
}

/** Deterministic JSON text of a manifest (sorted paths). */
export function serialiseManifest(files: Map<string, Record<string, string>>): string {
    const sorted: Record<string, Record<string, string>> = {};
    for (const path of [...files.keys()].sort()) sorted[path] = files.get(path)!;
    return JSON.stringify({ version: 1, files: sorted }, null, 1) + '\n';
}

/**
 * Without a manifest entry, a region counts as default when it holds nothing but blanks and the
 * generator's `//TODO` placeholder: anything else is kept as user code.
 */
export function looksLikeDefault(content: string): boolean {
    return content.replace(/\/\/\s*TODO/g, '').trim() === '';
}
