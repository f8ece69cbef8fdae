/**
 * Which project a `.scenario` file is about (docs/simulation.md "Editing scenarios"): the Cactal
 * files of the nearest folder, from the scenario's own folder upwards, that holds `.contract`
 * documents of the workspace (`contract simulate DIR` takes that folder; `DIR/scenarios/x.scenario`
 * finds `DIR`). Several projects in one workspace (the repository's examples/) stay apart.
 */
import { URI, type LangiumDocuments } from 'langium';
import { isModel, type Model } from '../../generated/ast.js';

export const SCENARIO_LANGUAGE_ID = 'cactal-scenario';
export const SCENARIO_EXTENSION = '.scenario';

export function isScenarioUri(uri: string | undefined): boolean {
    if (typeof uri !== 'string') return false;
    const path = uri.split(/[?#]/)[0]!;
    return path.endsWith(SCENARIO_EXTENSION);
}

export interface ScenarioProject {
    /** The folder URI of the project (ends with '/'), undefined when no Cactal file was found. */
    folder?: string;
    models: Model[];
}

/** Folder URIs from the file's own folder up to the root: `file:///a/b/c.scenario` -> `file:///a/b/`, `file:///a/`, `file:///`. */
function ancestorFolders(uri: string): string[] {
    const m = /^([a-z][a-z0-9+.-]*:\/\/[^/]*)(\/.*)?$/i.exec(uri.split(/[?#]/)[0]!);
    if (!m) return [];
    const authority = m[1]!;
    const segments = (m[2] ?? '/').split('/').slice(1, -1);
    const out: string[] = [];
    for (let n = segments.length; n >= 0; n--) out.push(`${authority}/${segments.slice(0, n).map((s) => `${s}/`).join('')}`);
    return out;
}

export function scenarioProject(documents: LangiumDocuments, scenarioUri: string): ScenarioProject {
    const models: Array<{ uri: string; model: Model }> = [];
    for (const doc of documents.all) {
        const model = doc.parseResult?.value;
        if (isModel(model)) models.push({ uri: doc.uri.toString(), model });
    }
    // Same spelling as the documents' URIs (a client may encode `:` or spaces differently).
    let normalized = scenarioUri;
    try {
        normalized = URI.parse(scenarioUri).toString();
    } catch {
        // not a URI: compared as written
    }
    for (const folder of ancestorFolders(normalized)) {
        const inside = models.filter((m) => m.uri.startsWith(folder));
        if (inside.length) return { folder, models: inside.map((m) => m.model) };
    }
    return { models: [] };
}
