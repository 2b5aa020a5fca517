// Knows the price of apples, works out the price of pears when asked.
price(apple, cheap).
stock(apple).

+?price(pear, P) <- P = dear.
