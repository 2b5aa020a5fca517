// expect: 7:1 expected `}` to close the sub-plans
// Sub-plans whose braces are never closed.
+!emptyDishwasher <- !unloadNext.
{
    +!unloadNext : inDishwasher(C) <- pickUp(C); !unloadNext.
    +!unloadNext.
