export { writeTree, type GeneratedFile, type WriteTreeOptions } from './write-tree.js';
export { emptyReport, formatProblem, type GenerationReport, type GenerationProblem } from './report.js';
export { ORPHANS_DIR } from './orphans.js';
export { MANIFEST_NAME } from './manifest.js';
export { renameInGeneratedTree, renameRegionId, renameGeneratedName, type RenameGeneratedReport } from './rename-generated.js';
export {
    renameIdentifierInGeneratedTree, renameIdentifiersInGeneratedTree, identifierRenames, findRegionMentions, mentionMatcher, oldNamesMatcher, carryRefusedMessage,
    type IdentifierCarryReport, type RegionMention, type EnumerationNames,
} from './rename-user-code.js';
export { cWords, renameIdentifier, type CWord, type WordContext } from './c-identifiers.js';
export { writeFileAtomic, isAtomicTempFile } from './atomic-write.js';
export { UnsafePathError, checkTreePath, checkTreeRoot, lstatInTree, treePathProblem } from './safe-paths.js';
export { OutputTree } from './output-tree.js';
export { PROC_FD, fdPath, openDirNoFollow, requireProcFd, closeQuietly, type DirOpen, type NotAFolder } from './dir-fd.js';
export { manifestEntryProblem, loadManifest, skeletonText, skeletonHash, type ManifestLoad, type LoadedManifest } from './manifest.js';
export { STALE_TEMP_AGE_MS, removeStaleTemps } from './stale-temp.js';
export { TREE_LOCK_NAME, LOCK_WAIT_MS, TreeLockedError, tryTreeLock, lockTree, lockTreeSync, TREE_WRITERS } from './tree-lock.js';
export {
    RENAME_JOURNAL_NAME, writeRenameJournal, removeRenameJournal, finishInterruptedRename, describeFinishedRename, sha256, realOrSelf,
    type RenameJournal, type RenameJournalFile, type FinishedRename, type FinishedRenameDescription,
} from './rename-journal.js';
export { carryRenameIntoTree, type TreeRename, type TreeCarryOver } from './carry-rename.js';
export { runJournaledRename, RenameStepError, type RenameStep, type JournaledRenameOptions } from './journaled-rename.js';
export { REGION_COPY_NAME, loadRegionCopy, type RegionBodies } from './region-copy.js';
export { recordUserCode, userCodeOf, userCodeOfFiles, type UserCodeOfFile, type UserCodeRecord } from './record-user-code.js';
