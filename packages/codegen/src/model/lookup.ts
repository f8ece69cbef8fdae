import type { Architecture, Datatype, EnumDecl, FunctionPrototype, Module, Schema, Supervisor, TypeRef } from './architecture.js';

/** Name-indexed access to an architecture's entities (all names are unique project-wide). */
export class ArchitectureIndex {
    readonly datatypes = new Map<string, Datatype>();
    readonly enums = new Map<string, EnumDecl>();
    readonly functions = new Map<string, FunctionPrototype>();
    readonly modules = new Map<string, Module>();
    readonly schemas = new Map<string, Schema>();
    readonly supervisors = new Map<string, Supervisor>();

    constructor(readonly architecture: Architecture) {
        for (const d of architecture.datatypes) this.datatypes.set(d.name, d);
        for (const e of architecture.enums ?? []) this.enums.set(e.name, e);
        for (const f of architecture.functions) this.functions.set(f.name, f);
        for (const m of architecture.modules) this.modules.set(m.name, m);
        for (const s of architecture.schemas) this.schemas.set(s.name, s);
        for (const s of architecture.supervisors) this.supervisors.set(s.name, s);
    }

    datatype(name: string): Datatype {
        const d = this.datatypes.get(name);
        if (!d) throw new Error(`unknown datatype '${name}'`);
        return d;
    }

    enumDecl(name: string): EnumDecl {
        const e = this.enums.get(name);
        if (!e) throw new Error(`unknown enumeration '${name}'`);
        return e;
    }

    /**
     * The datatypes and enumerations (each has a `common/Shared<Name>.h`) a type depends on,
     * itself included, dependencies first; arrays depend on their element type.
     */
    datatypeClosure(type: TypeRef, into: string[] = []): string[] {
        if ('array' in type) return this.datatypeClosure(type.array, into);
        if ('enum' in type && !into.includes(type.enum)) into.push(type.enum);
        if ('datatype' in type && !into.includes(type.datatype)) {
            for (const f of this.datatype(type.datatype).fields) this.datatypeClosure(f.type, into);
            into.push(type.datatype);
        }
        return into;
    }
}

/** The named type (datatype or enumeration) of a type or of its elements, if any: its header is `Shared<Name>.h`. */
export function namedTypeOf(t: TypeRef): string | undefined {
    if ('array' in t) return namedTypeOf(t.array);
    if ('datatype' in t) return t.datatype;
    if ('enum' in t) return t.enum;
    return undefined;
}

/** Cactal spelling of a type: `int`, `TypeA`, `Mode`, `float[3][3]`. */
export function typeName(t: TypeRef): string {
    if ('array' in t) {
        const sizes: number[] = [];
        let e: TypeRef = t;
        while ('array' in e) {
            sizes.push(e.size);
            e = e.array;
        }
        return `${typeName(e)}${sizes.map((n) => `[${n}]`).join('')}`;
    }
    if ('enum' in t) return t.enum;
    return 'primitive' in t ? t.primitive : t.datatype;
}

export function isString(t: TypeRef): boolean {
    return 'primitive' in t && t.primitive === 'string';
}
