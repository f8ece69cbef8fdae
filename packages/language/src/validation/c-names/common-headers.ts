/**
 * The `common/` headers of datatypes and function prototypes (docs/codegen.md): two elements must
 * not share a header file or an include guard, or one header would replace or hide the other
 * (docs/language-reference.md, "Reserved names"). Keyed once per workspace build.
 */
import { commonHeaderKeys } from './generated-code-names.js';

export interface HeaderOwner {
    readonly kind: 'datatype' | 'function';
    readonly name: string;
}

export interface HeaderClash {
    readonly other: HeaderOwner;
    /** What they would share, in words: `include guard SHARED_POSE_H`, `header file common/SharedPose.h`. */
    readonly shared: string;
}

const same = (a: HeaderOwner, b: HeaderOwner) => a.kind === b.kind && a.name === b.name;

export class CommonHeaderIndex {
    private readonly owners = new Map<string, HeaderOwner[]>();

    constructor(owners: Iterable<HeaderOwner>) {
        for (const owner of owners) {
            for (const key of keysOf(owner)) {
                const list = this.owners.get(key) ?? [];
                if (!list.some((o) => same(o, owner))) list.push(owner);
                this.owners.set(key, list);
            }
        }
    }

    /** Another element whose header would share the guard (first) or the file name with `owner`'s. */
    clash(owner: HeaderOwner): HeaderClash | undefined {
        const keys = commonHeaderKeys(owner.kind, owner.name);
        const [guard, file] = keysOf(owner);
        const byGuard = this.owners.get(guard!)?.find((o) => !same(o, owner));
        if (byGuard) return { other: byGuard, shared: `include guard ${keys.guard}` };
        const byFile = this.owners.get(file!)?.find((o) => !same(o, owner));
        if (byFile) return { other: byFile, shared: `header file common/${keys.file}` };
        return undefined;
    }
}

/** File names compare without case: a checkout on a case-insensitive file system would merge them. */
function keysOf(owner: HeaderOwner): [string, string] {
    const keys = commonHeaderKeys(owner.kind, owner.name);
    return [`guard:${keys.guard}`, `file:${keys.file.toLowerCase()}`];
}
