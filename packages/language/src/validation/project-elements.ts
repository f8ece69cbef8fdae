/**
 * Project-wide elements that have no name in the index (the scheduler configuration), found by
 * scanning the workspace's documents once per workspace build.
 */
import { WorkspaceCache, type LangiumCoreServices, type URI } from 'langium';
import { isModel, isSchedulerConfiguration, type SchedulerConfiguration } from '../generated/ast.js';

export interface Located<T> {
    node: T;
    uri: URI;
}

export class ProjectElements {
    private readonly cache: WorkspaceCache<string, Array<Located<SchedulerConfiguration>>>;

    constructor(private readonly services: LangiumCoreServices) {
        this.cache = new WorkspaceCache(services.shared);
    }

    /** Every scheduler configuration of the project, in document order. */
    schedulerConfigurations(): Array<Located<SchedulerConfiguration>> {
        return this.cache.get('scheduler', () => {
            const found: Array<Located<SchedulerConfiguration>> = [];
            for (const doc of this.services.shared.workspace.LangiumDocuments.all) {
                const root = doc.parseResult?.value;
                if (!isModel(root)) continue;
                for (const element of root.elements) {
                    if (isSchedulerConfiguration(element)) found.push({ node: element, uri: doc.uri });
                }
            }
            return found;
        });
    }
}
