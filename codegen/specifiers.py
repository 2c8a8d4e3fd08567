"""Parsing of macro arguments: SPFUNCTION(BlueprintCallable, meta=(DeterminesOutputType="uclass")).

Arguments arrive as the stringified macro text. Items are `Key` or `Key=Value`; `meta=(...)` is
flattened into its items. Unknown keys are errors, so that a misspelt specifier is never ignored.
"""

from __future__ import annotations

KNOWN: dict[str, frozenset[str]] = {
    "class": frozenset(
        {"Abstract", "BlueprintType", "Blueprintable", "NotBlueprintable", "Category", "DisplayName", "Config"}
    ),
    # TypedDict: the struct crosses to Python as a dict typed by a TypedDict, every field present (an array
    # field left without data is an error when the struct is returned). TypedDict, Partial: total=False,
    # and array fields that hold no data are left out, so a result carries just the entries produced.
    "struct": frozenset({"BlueprintType", "Category", "DisplayName", "TypedDict", "Partial"}),
    "enum": frozenset({"BlueprintType", "Category", "DisplayName"}),
    "property": frozenset(
        {
            "EditAnywhere", "EditDefaultsOnly", "EditInstanceOnly", "VisibleAnywhere", "VisibleDefaultsOnly",
            "VisibleInstanceOnly", "BlueprintReadWrite", "BlueprintReadOnly", "ReadOnly", "Setter", "Getter",
            "Category", "Transient", "DisplayName", "ToolTip", "AllowPrivateAccess", "Units", "ClampMin",
            "ClampMax", "NotNull",
        }
    ),
    "function": frozenset(
        {
            "BlueprintCallable", "BlueprintPure", "CallInEditor", "Category", "DeterminesOutputType", "NotNull",
            "DisplayName", "ToolTip",
        }
    ),
}


class SpecifierError(ValueError):
    pass


def _split_top_level(text: str) -> list[str]:
    items, depth, quote, current = [], 0, "", []
    for ch in text:
        if quote:
            current.append(ch)
            if ch == quote:
                quote = ""
            continue
        if ch in "\"'":
            quote = ch
        elif ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
            if depth < 0:
                raise SpecifierError("unbalanced ')'")
        elif ch == "," and depth == 0:
            items.append("".join(current).strip())
            current = []
            continue
        current.append(ch)
    if depth != 0 or quote:
        raise SpecifierError("unbalanced parentheses or quotes")
    tail = "".join(current).strip()
    if tail or items:
        items.append(tail)
    return items


def parse(kind: str, text: str) -> tuple[tuple[str, str], ...]:
    """Returns (key, value) pairs in source order; value is "" for a bare key."""
    result: list[tuple[str, str]] = []
    for item in _split_top_level(text.strip()):
        if not item:
            raise SpecifierError("empty specifier")
        key, sep, value = (part.strip() for part in item.partition("="))
        if sep and not value:
            raise SpecifierError(f"specifier '{key}' has no value")
        if key.lower() == "meta":
            if not (value.startswith("(") and value.endswith(")")):
                raise SpecifierError("meta must be written meta=(Key=Value, ...)")
            result.extend(parse(kind, value[1:-1]))
            continue
        if not key.isidentifier():
            raise SpecifierError(f"'{item}' is not a specifier")
        if key not in KNOWN[kind]:
            raise SpecifierError(f"unknown specifier '{key}' (known: {', '.join(sorted(KNOWN[kind]))})")
        result.append((key, value.strip("\"'")))
    return tuple(result)


def lookup(specifiers: tuple[tuple[str, str], ...], key: str) -> str | None:
    for k, v in specifiers:
        if k == key:
            return v
    return None


def has(specifiers: tuple[tuple[str, str], ...], key: str) -> bool:
    return any(k == key for k, _ in specifiers)
