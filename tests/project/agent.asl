+!g <- navigateTo(table).
