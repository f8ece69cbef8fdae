/**
 * The `.gitignore` that `contract new` writes (docs/getting-started.md "Keeping a project in
 * git"): what ContrACT Studio writes into a project that is no source, and the last generation's copy
 * of the protected regions' code (a copy of what the committed generated files hold, written anew by
 * each generate and build of the checkout). `src-gen/` with its manifest and `src-gen/orphans/` (the
 * only copy of code the generator moved aside) are committed.
 */
export const PROJECT_GITIGNORE = [
    '# contract run\'s logs (the last run, and previous/ runs before it)',
    'logs/',
    '# the generated tree\'s write lock, and the journal of a rename being done (docs/codegen.md)',
    'src-gen/.contract-lock',
    'src-gen/.contract-rename.json',
    '# the last generation\'s copy of your protected regions\' code, which brings a deleted generated file\'s code',
    '# back (docs/codegen.md "A generated file deleted"): each generate and build writes it from this checkout\'s',
    '# files; the files themselves are committed, and a committed copy goes stale at each region edit committed',
    '# without a generate (CI\'s `contract generate . && git diff --exit-code -- src-gen` then fails on it)',
    'src-gen/.contract-regions.json',
    '# a make run by hand in src-gen/generated/architecture (contract build works in a private copy)',
    '*.o',
    '',
].join('\n');
