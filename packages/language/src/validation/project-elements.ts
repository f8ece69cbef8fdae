/**
 * Project-wide elements that have no name in the index (the scheduler configuration), found by
 * scanning the documents of a project (scoping/projects.ts) once per workspace build.
 */
import { AstUtils, WorkspaceCache, type AstNode, type URI } from 'langium';
import { isModel, isSchedulerConfiguration, type SchedulerConfiguration } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { otherLocations } from './locations.js';

export interface Located<T> {
    node: T;
    uri: URI;
}

export class ProjectElements {
    private readonly cache: WorkspaceCache<string, Array<Located<SchedulerConfiguration>>>;

    constructor(private readonly services: CactalServices) {
        this.cache = new WorkspaceCache(services.shared);
    }

    /** Every scheduler configuration of the project of `context`, in document order. */
    schedulerConfigurations(context: AstNode): Array<Located<SchedulerConfiguration>> {
        const uri = AstUtils.getDocument(context).uri;
        const projects = this.services.projects.Projects;
        return this.cache.get(projects.keyOf(uri), () => {
            const found: Array<Located<SchedulerConfiguration>> = [];
            for (const doc of projects.documentsOf(uri)) {
                const root = doc.parseResult?.value;
                if (!isModel(root)) continue;
                for (const element of root.elements) {
                    if (isSchedulerConfiguration(element)) found.push({ node: element, uri: doc.uri });
                }
            }
            return found;
        });
    }

    /** Where the other occurrences of `node`'s kind are, for its message (locations.ts). */
    otherLocations(node: AstNode, occurrences: URI[]): string {
        return otherLocations(this.services.projects.Projects, AstUtils.getDocument(node).uri, occurrences);
    }
}
