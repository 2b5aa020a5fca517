// expect: 3:11 expects a file name in a string
// The file name of an include is a string.
{ include(kitchen_plans) }
