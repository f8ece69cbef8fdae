/**
 * A rename carried into a generated tree: the paths and region IDs of an entity that names
 * generated files (rename-generated.ts), then the C identifiers of the user code
 * (rename-user-code.ts). One step of every rename (journaled-rename.ts) and of the finishing of an
 * interrupted one (rename-journal.ts).
 */
import { renameInGeneratedTree, type RenameGeneratedReport } from './rename-generated.js';
import type { RenameJournal } from './rename-journal.js';
import { renameIdentifiersInGeneratedTree, type IdentifierCarryReport } from './rename-user-code.js';

/** What a rename changes in the generated tree, as its journal says it. */
export type TreeRename = Pick<RenameJournal, 'kind' | 'oldName' | 'newName' | 'generatedNames' | 'identifiers' | 'identifierOwner'>;

/** What the carry-over did: the paths and region IDs moved (an entity naming generated files), the identifiers rewritten (names the user code uses). */
export interface TreeCarryOver {
    moved?: RenameGeneratedReport;
    code?: IdentifierCarryReport;
}

/**
 * Carries `rename` into generated tree `srcGen`: the paths and region IDs, then the identifiers in
 * the protected regions' code. Idempotent: what moved already is not there any more. The caller
 * holds the tree's lock.
 */
export async function carryRenameIntoTree(srcGen: string, rename: TreeRename): Promise<TreeCarryOver> {
    const carried: TreeCarryOver = {};
    // (a journal's kind 'entity' is the IDE's rename of an entity of unknown kind: any kind's names move)
    if (rename.generatedNames) carried.moved = await renameInGeneratedTree(srcGen, rename.oldName, rename.newName, rename.kind === 'entity' ? undefined : rename.kind);
    if (rename.identifiers.length > 0) carried.code = renameIdentifiersInGeneratedTree(srcGen, new Map(rename.identifiers), rename.identifierOwner);
    return carried;
}
